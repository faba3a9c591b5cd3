// Compact STRP (codec 1): a lossless recoding of a raw STRP payload against
// its BASE, layout in docs/format.md "Compact STRP". A strip's every window
// of three indices is a BASE triangle or a degenerate swap, so an index is
// nearly always the third vertex of a BASE triangle on the edge of the two
// indices before it: one of at most two in a manifold mesh, and most often
// the one that is not the index before those (the strip moves on rather
// than back). The raw payload spends bits(V) bits on each.
//
// Choices:
// - Each index from the third on is a symbol: the candidates (third
//   vertices of the triangles on the edge, the one other than the index
//   three back first), then a repeat of either index of the edge (swaps),
//   then an escape to the difference from the previous index. Exp-Golomb
//   with the encoder's order.
// - A strip's first index as the difference from the previous strip's
//   last (the stripifier walks the mesh, so strips start near where the
//   last one ended); its second as an index into the neighbours of the
//   first (from its first 64 BASE triangles), or an escape.
// - Triangles are looked up in each vertex's BASE triangle list, of which
//   only the first 64 are scanned, so hostile meshes cannot make a lookup
//   cost more than a constant.
// - The decoder writes the strips with the raw writer; the encoder refuses
//   raw payloads the raw writer would not write byte for byte.
#include "formats/sections/strp_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/strp.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int { kLength, kFirst, kSecond, kNext, kEscape, kContextCount };

constexpr size_t kScannedTriangles = 64;

Status bad_compact(const std::string& detail) {
  return malformed_section(kStrpTag, "compact: " + detail);
}

// BASE's triangles per vertex, for the lookups of the file comment.
class Adjacency {
 public:
  explicit Adjacency(const TriangleMesh& base)
      : triangles_(base.triangles), incident_(base.vertex_count()) {
    for (uint32_t t = 0; t < triangles_.size(); ++t) {
      for (uint32_t v : triangles_[t])
        incident_[v].push_back(t);
    }
  }

  // The distinct third vertices of the triangles holding a and b; `back`
  // (the index before them, or none) goes last.
  void third_vertices(uint32_t a, uint32_t b, uint32_t back, std::vector<uint32_t>* out) const {
    out->clear();
    bool has_back = false;
    const std::vector<uint32_t>& list = incident_[a];
    for (size_t i = 0; i < list.size() && i < kScannedTriangles; ++i) {
      const Triangle& t = triangles_[list[i]];
      if (t[0] != b && t[1] != b && t[2] != b) continue;
      for (uint32_t x : t) {
        if (x == a || x == b) continue;
        if (x == back) {
          has_back = true;
          continue;
        }
        bool seen = false;
        for (uint32_t y : *out)
          seen = seen || y == x;
        if (!seen) out->push_back(x);
      }
    }
    if (has_back) out->push_back(back);
  }

  void neighbours(uint32_t a, std::vector<uint32_t>* out) const {
    out->clear();
    const std::vector<uint32_t>& list = incident_[a];
    for (size_t i = 0; i < list.size() && i < kScannedTriangles; ++i) {
      for (uint32_t x : triangles_[list[i]]) {
        if (x == a) continue;
        bool seen = false;
        for (uint32_t y : *out)
          seen = seen || y == x;
        if (!seen) out->push_back(x);
      }
    }
  }

 private:
  std::vector<Triangle> triangles_;
  std::vector<std::vector<uint32_t>> incident_;
};

constexpr uint32_t kNoIndex = UINT32_MAX;

void encode_pass(const TriangleStrips& strips, const Adjacency& adjacency,
                 CompactStreamWriter* out) {
  std::vector<uint32_t> list;
  uint32_t last = 0;
  for (size_t s = 0; s < strips.strip_count(); ++s) {
    const uint32_t* v = strips.indices.data() + strips.first[s];
    const size_t n = strips.length(s);
    out->golomb(kLength, n - 3);
    out->golomb(kFirst, zigzag64(int64_t{v[0]} - int64_t{last}));
    adjacency.neighbours(v[0], &list);
    size_t at = 0;
    while (at < list.size() && list[at] != v[1])
      ++at;
    out->golomb(kSecond, at < list.size() ? at + 1 : 0);
    if (at == list.size()) out->golomb(kEscape, zigzag64(int64_t{v[1]} - int64_t{v[0]}));
    for (size_t i = 2; i < n; ++i) {
      adjacency.third_vertices(v[i - 2], v[i - 1], i >= 3 ? v[i - 3] : kNoIndex, &list);
      list.push_back(v[i - 2]);
      list.push_back(v[i - 1]);
      at = 0;
      while (at < list.size() && list[at] != v[i])
        ++at;
      out->golomb(kNext, at);
      if (at == list.size()) out->golomb(kEscape, zigzag64(int64_t{v[i]} - int64_t{v[i - 1]}));
    }
    last = v[n - 1];
  }
}

}  // namespace

Result<Bytes> encode_strp_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(TriangleStrips strips, decode_strp(raw, raw_size));
    if (strips.vertex_count != base.vertex_count()) {
      return invalid_input(string_printf("cannot encode compact STRP: %u vertices, BASE has %zu",
                                         strips.vertex_count, base.vertex_count()));
    }
    LODBAKE_ASSIGN_OR_RETURN(Bytes canonical, encode_strp(strips));
    LODBAKE_RETURN_IF_ERROR(
        require_canonical_layout(kStrpTag, canonical, raw, raw_size, "length width"));
    Bytes out(1 + kStrpFixedBytes);
    out[0] = kStrpCompactVersion;
    std::memcpy(out.data() + 1, raw, kStrpFixedBytes);
    const Adjacency adjacency(base);
    CompactStreamWriter stream(kContextCount);
    encode_pass(strips, adjacency, &stream);
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact STRP");
  }
}

Result<Bytes> decode_strp_compact(const uint8_t* data, size_t size, const TriangleMesh& base) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kStrpTag, data, size, kStrpFixedBytes, kStrpCompactVersion));
    const uint8_t* fixed = data + 1;
    uint32_t vertex_count = 0, strip_count = 0, index_count = 0;
    std::memcpy(&vertex_count, fixed, 4);
    std::memcpy(&strip_count, fixed + 4, 4);
    std::memcpy(&index_count, fixed + 8, 4);
    if (vertex_count != base.vertex_count())
      return bad_compact(
          string_printf("%u vertices, BASE has %zu", vertex_count, base.vertex_count()));
    if (uint64_t{strip_count} * 3 > index_count)
      return bad_compact(string_printf("%u strips cannot fill %u indices of at least 3 each",
                                       strip_count, index_count));
    CompactStreamReader in;
    if (!in.start(fixed + kStrpFixedBytes, size - 1 - kStrpFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // Every index takes at least one code bit.
    if (index_count > in.bits_left()) {
      return bad_compact(string_printf("%u indices need at least as many bits, %" PRIu64 " remain",
                                       index_count, in.bits_left()));
    }
    TriangleStrips strips;
    strips.vertex_count = vertex_count;
    strips.indices.reserve(index_count);
    strips.first.reserve(uint64_t{strip_count} + 1);
    const Adjacency adjacency(base);
    std::vector<uint32_t> list;
    uint64_t value = 0;
    uint32_t last = 0;
    auto index_after = [&](uint32_t from, uint64_t code, uint32_t* out) {
      const int64_t v = int64_t{from} + unzigzag64(code);
      if (v < 0 || v >= vertex_count) return false;
      *out = static_cast<uint32_t>(v);
      return true;
    };
    for (uint32_t s = 0; s < strip_count; ++s) {
      auto bad_code = [&](const char* what) {
        return bad_compact(
            string_printf("truncated or out-of-range code in the %s of strip %u", what, s));
      };
      if (!in.golomb(kLength, &value)) return bad_code("length");
      if (value + 3 > index_count - strips.indices.size())
        return bad_compact(
            string_printf("strip %u has indices beyond the header's %u", s, index_count));
      const size_t n = static_cast<size_t>(value + 3);
      uint32_t v0 = 0, v1 = 0;
      if (!in.golomb(kFirst, &value) || !index_after(last, value, &v0)) return bad_code("start");
      strips.indices.push_back(v0);
      adjacency.neighbours(v0, &list);
      if (!in.golomb(kSecond, &value)) return bad_code("start");
      if (value == 0) {
        if (!in.golomb(kEscape, &value) || !index_after(v0, value, &v1)) return bad_code("start");
      } else if (value <= list.size()) {
        v1 = list[value - 1];
      } else {
        return bad_code("start");
      }
      strips.indices.push_back(v1);
      for (size_t i = 2; i < n; ++i) {
        const uint32_t* v = strips.indices.data() + strips.indices.size() - i;
        adjacency.third_vertices(v[i - 2], v[i - 1], i >= 3 ? v[i - 3] : kNoIndex, &list);
        list.push_back(v[i - 2]);
        list.push_back(v[i - 1]);
        if (!in.golomb(kNext, &value)) return bad_code("indices");
        uint32_t next = 0;
        if (value < list.size()) {
          next = list[value];
        } else if (value > list.size() || !in.golomb(kEscape, &value) ||
                   !index_after(v[i - 1], value, &next)) {
          return bad_code("indices");
        }
        strips.indices.push_back(next);
      }
      strips.first.push_back(static_cast<uint32_t>(strips.indices.size()));
      last = strips.indices.back();
    }
    if (strips.indices.size() != index_count)
      return bad_compact(string_printf("the strips hold %zu indices, the header says %u",
                                       strips.indices.size(), index_count));
    return finish_compact_decode(kStrpTag, in, encode_strp(strips), fixed, kStrpFixedBytes,
                                 "strips");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact STRP");
  }
}

}  // namespace lodbake
