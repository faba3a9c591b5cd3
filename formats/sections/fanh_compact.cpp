// Compact FANH (codec 1): a lossless recoding of a raw FANH payload against
// its BASE, layout in docs/format.md "Compact FANH". A fan-merge hierarchy
// (Livny, Sokolovsky & El-Sana 2007) stores, for every collapsed child, the
// BASE triangles its collapse removes and modifies: 72% of the raw bits on
// the Stanford bunny (17-bit triangle ids). Replaying the merges over
// BASE's triangles gives those lists exactly.
//
// Choices:
// - The replay mirrors the fan-merge builder's mesh state
//   (lib/fanmerge/fan_mesh_state.h): per vertex its triangles in list
//   order (BASE order, push_back, swap-remove), so a child's removed list
//   (its triangles that hold the centre) and modified list (the others) are
//   predicted in the order the builder wrote them. One bit says "as
//   predicted"; otherwise the counts and the ids follow explicitly
//   (differences from the previous explicit id), so a list the prediction
//   misses (after refused merges the builder undid, whose undo reorders
//   lists) still round-trips. Predictions are made only for stars of at
//   most 64 triangles: every predicted entry then costs at least 1/128 bit,
//   which bounds the decoded lists by the input size.
// - A child is named by its vertex (the vertex its node stands for) and is
//   that vertex's topmost node; link vertices are coded as their index in
//   the centre's neighbours before the merge (from its first 64 triangles),
//   with an escape to the plain id. A centre is a plain bits(V) id (merges
//   come in error order, anywhere on the mesh).
// - Errors as zigzag differences of their bit patterns from the previous
//   merge's.
// - The decoder rebuilds the hierarchy and writes it with the raw writer,
//   so its output obeys FANH's structural rules; the encoder refuses raw
//   payloads the raw writer would not write byte for byte.
#include "formats/sections/fanh_compact.h"

#include <algorithm>
#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/fan_hierarchy.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/fanh.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int { kError, kChildCount, kLinkVertex, kListCount, kTriangle, kContextCount };

constexpr size_t kMaxPredictedStar = 64;
constexpr size_t kMaxList = 256;
constexpr size_t kNeighbourTriangles = 64;

Status bad_compact(const std::string& detail) {
  return malformed_section(kFanhTag, "compact: " + detail);
}

// BASE's triangles under the merges so far (see the file comment).
class Replay {
 public:
  explicit Replay(const TriangleMesh& base)
      : corners_(base.triangles), incident_(base.vertex_count()) {
    for (uint32_t t = 0; t < corners_.size(); ++t) {
      for (uint32_t v : corners_[t])
        if (incident_[v].size() < kMaxList) incident_[v].push_back(t);
    }
  }

  // The centre's neighbours from its first triangles, first seen first.
  void neighbours(uint32_t v, std::vector<uint32_t>* out) const {
    out->clear();
    const std::vector<uint32_t>& star = incident_[v];
    for (size_t i = 0; i < star.size() && i < kNeighbourTriangles; ++i) {
      for (uint32_t x : corners_[star[i]]) {
        if (x == v) continue;
        bool seen = false;
        for (uint32_t y : *out)
          seen = seen || y == x;
        if (!seen) out->push_back(x);
      }
    }
  }

  // The lists collapsing u into v would give, when u's star is small.
  bool predict(uint32_t u, uint32_t v, std::vector<uint32_t>* removed,
               std::vector<uint32_t>* modified) const {
    const std::vector<uint32_t>& star = incident_[u];
    if (star.size() > kMaxPredictedStar) return false;
    removed->clear();
    modified->clear();
    for (uint32_t t : star) {
      const Triangle& c = corners_[t];
      (c[0] == v || c[1] == v || c[2] == v ? removed : modified)->push_back(t);
    }
    return true;
  }

  // As FanMeshState::collapse(), for any lists (hostile ones included).
  void collapse(uint32_t u, uint32_t v, const uint32_t* removed, size_t removed_count,
                const uint32_t* modified, size_t modified_count) {
    for (size_t i = 0; i < removed_count; ++i) {
      for (uint32_t x : corners_[removed[i]])
        remove(x, removed[i]);
    }
    for (size_t i = 0; i < modified_count; ++i) {
      const uint32_t t = modified[i];
      for (uint32_t& x : corners_[t])
        if (x == u) x = v;
      remove(u, t);
      // Capped (as in the constructor), so that hostile lists cannot make
      // every removal scan far; a list this long is never predicted from.
      if (incident_[v].size() < kMaxList) incident_[v].push_back(t);
    }
  }

 private:
  void remove(uint32_t v, uint32_t t) {
    std::vector<uint32_t>& list = incident_[v];
    for (size_t i = 0; i < list.size(); ++i) {
      if (list[i] == t) {
        list[i] = list.back();
        list.pop_back();
        return;
      }
    }
  }

  std::vector<Triangle> corners_;
  std::vector<std::vector<uint32_t>> incident_;
};

// The encoder's walk. \return false when a child is not the topmost node
// of its vertex.
bool encode_pass(const FanHierarchy& h, const TriangleMesh& base, CompactStreamWriter* out) {
  const uint32_t v_count = h.vertex_count;
  const int vertex_bits = bits_for_count(v_count);
  Replay replay(base);
  std::vector<uint32_t> top(v_count), rep(h.node_count());
  for (uint32_t v = 0; v < v_count; ++v)
    top[v] = rep[v] = v;
  std::vector<uint32_t> link, removed, modified;
  uint32_t previous_error = 0;
  uint32_t previous_triangle = 0;
  for (size_t i = 0; i < h.internal_count(); ++i) {
    const uint32_t bits = float_bits(h.error[i]);
    out->golomb(kError, zigzag64(int64_t{bits} - int64_t{previous_error}));
    previous_error = bits;
    const uint32_t c0 = h.child_start[i], c1 = h.child_start[i + 1];
    out->golomb(kChildCount, c1 - c0 - 2);
    const uint32_t centre = rep[h.children[c0]];
    if (top[centre] != h.children[c0]) return false;
    out->bits(centre, vertex_bits);
    replay.neighbours(centre, &link);
    for (uint32_t j = c0 + 1; j < c1; ++j) {
      const uint32_t u = rep[h.children[j]];
      if (top[u] != h.children[j]) return false;
      size_t at = 0;
      while (at < link.size() && link[at] != u)
        ++at;
      out->golomb(kLinkVertex, at < link.size() ? at + 1 : 0);
      if (at == link.size()) out->bits(u, vertex_bits);
      const uint32_t* r = h.removed.data() + h.removed_start[j];
      const uint32_t* m = h.modified.data() + h.modified_start[j];
      const uint32_t nr = h.removed_start[j + 1] - h.removed_start[j];
      const uint32_t nm = h.modified_start[j + 1] - h.modified_start[j];
      bool hit = false;
      if (replay.predict(u, centre, &removed, &modified)) {
        hit = removed.size() == nr && modified.size() == nm &&
              std::equal(removed.begin(), removed.end(), r) &&
              std::equal(modified.begin(), modified.end(), m);
        out->bits(hit, 1);
      }
      if (!hit) {
        out->golomb(kListCount, nr);
        out->golomb(kListCount, nm);
        for (const uint32_t* list : {r, m}) {
          const uint32_t n = list == r ? nr : nm;
          for (uint32_t k = 0; k < n; ++k) {
            out->golomb(kTriangle, zigzag64(int64_t{list[k]} - int64_t{previous_triangle}));
            previous_triangle = list[k];
          }
        }
      }
      replay.collapse(u, centre, r, nr, m, nm);
    }
    const uint32_t node = v_count + static_cast<uint32_t>(i);
    rep[node] = centre;
    top[centre] = node;
  }
  return true;
}

}  // namespace

Result<Bytes> encode_fanh_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(FanHierarchy h, decode_fanh(raw, raw_size));
    if (h.vertex_count != base.vertex_count() || h.triangle_count != base.triangle_count()) {
      return invalid_input(string_printf(
          "cannot encode compact FANH: %u vertices and %u triangles, BASE has %zu and %zu",
          h.vertex_count, h.triangle_count, base.vertex_count(), base.triangle_count()));
    }
    LODBAKE_ASSIGN_OR_RETURN(Bytes canonical, encode_fanh(h));
    LODBAKE_RETURN_IF_ERROR(
        require_canonical_layout(kFanhTag, canonical, raw, raw_size, "count widths"));
    Bytes out(1 + kFanhFixedBytes);
    out[0] = kFanhCompactVersion;
    std::memcpy(out.data() + 1, raw, kFanhFixedBytes);
    CompactStreamWriter stream(kContextCount);
    if (!encode_pass(h, base, &stream)) {
      return unsupported(
          "FANH names a child that is not the topmost node of its vertex, which the compact "
          "codec cannot store");
    }
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact FANH");
  }
}

Result<Bytes> decode_fanh_compact(const uint8_t* data, size_t size, const TriangleMesh& base) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kFanhTag, data, size, kFanhFixedBytes, kFanhCompactVersion));
    const uint8_t* fixed = data + 1;
    uint32_t f[6] = {};
    std::memcpy(f, fixed, sizeof(f));
    const uint32_t v_count = f[0], t_count = f[1], internal = f[2], child_total = f[3],
                   removed_total = f[4], modified_total = f[5];
    if (v_count != base.vertex_count() || t_count != base.triangle_count()) {
      return bad_compact(string_printf("%u vertices and %u triangles, BASE has %zu and %zu",
                                       v_count, t_count, base.vertex_count(),
                                       base.triangle_count()));
    }
    if (uint64_t{v_count} + internal > UINT32_MAX || uint64_t{child_total} < 2 * uint64_t{internal})
      return bad_compact("the fixed fields' counts are inconsistent");
    CompactStreamReader in;
    if (!in.start(fixed + kFanhFixedBytes, size - 1 - kFanhFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // A merge takes at least its error and count codes, a collapsed child
    // its vertex code; list entries at least 1/128 bit (see the file
    // comment), explicit ones a bit each.
    const uint64_t collapsed = uint64_t{child_total} - internal;
    const uint64_t bits = in.bits_left();
    if (2 * uint64_t{internal} + collapsed > bits ||
        uint64_t{removed_total} + modified_total > 2 * kMaxPredictedStar * collapsed + bits) {
      return bad_compact(
          string_printf("%u merges, %u children and %u list entries need more "
                        "than the %" PRIu64 " bits that remain",
                        internal, child_total, removed_total + modified_total, bits));
    }
    FanHierarchy h;
    h.vertex_count = v_count;
    h.triangle_count = t_count;
    h.error.reserve(internal);
    h.child_start.reserve(uint64_t{internal} + 1);
    h.children.reserve(child_total);
    h.removed_start.reserve(uint64_t{child_total} + 1);
    h.modified_start.reserve(uint64_t{child_total} + 1);
    const int vertex_bits = bits_for_count(v_count);
    Replay replay(base);
    std::vector<uint32_t> top(v_count);
    for (uint32_t v = 0; v < v_count; ++v)
      top[v] = v;
    std::vector<uint32_t> link, removed, modified;
    uint32_t previous_error = 0;
    int64_t previous_triangle = 0;
    uint64_t value = 0;
    auto truncated = [](const char* what, uint32_t merge) {
      return bad_compact(
          string_printf("truncated or malformed code in the %s of merge %u", what, merge));
    };
    auto read_vertex = [&](uint32_t* v) {
      return in.bits(vertex_bits, &value) && value < v_count &&
             (*v = static_cast<uint32_t>(value), true);
    };
    for (uint32_t i = 0; i < internal; ++i) {
      if (!in.golomb(kError, &value)) return truncated("error", i);
      const int64_t error = int64_t{previous_error} + unzigzag64(value);
      if (error < 0 || error > UINT32_MAX) return bad_compact("error code out of range");
      previous_error = static_cast<uint32_t>(error);
      h.error.push_back(bits_float(previous_error));
      if (!in.golomb(kChildCount, &value)) return truncated("child count", i);
      if (value + 2 > child_total - h.children.size())
        return bad_compact(
            string_printf("merge %u has children beyond the header's %u", i, child_total));
      const uint32_t count = static_cast<uint32_t>(value + 2);
      uint32_t centre = 0;
      if (!read_vertex(&centre)) return truncated("centre", i);
      h.children.push_back(top[centre]);
      h.removed_start.push_back(static_cast<uint32_t>(h.removed.size()));
      h.modified_start.push_back(static_cast<uint32_t>(h.modified.size()));
      replay.neighbours(centre, &link);
      for (uint32_t j = 1; j < count; ++j) {
        if (!in.golomb(kLinkVertex, &value)) return truncated("children", i);
        uint32_t u = 0;
        if (value == 0) {
          if (!read_vertex(&u)) return truncated("children", i);
        } else if (value <= link.size()) {
          u = link[value - 1];
        } else {
          return bad_compact(
              string_printf("merge %u: link index past its %zu neighbours", i, link.size()));
        }
        h.children.push_back(top[u]);
        const size_t r0 = h.removed.size(), m0 = h.modified.size();
        uint64_t hit = 0;
        if (replay.predict(u, centre, &removed, &modified) && !in.bits(1, &hit))
          return truncated("lists", i);
        if (hit != 0) {
          if (removed.size() > removed_total - r0 || modified.size() > modified_total - m0)
            return bad_compact(string_printf("merge %u: lists beyond the header's", i));
          h.removed.insert(h.removed.end(), removed.begin(), removed.end());
          h.modified.insert(h.modified.end(), modified.begin(), modified.end());
        } else {
          uint64_t nr = 0, nm = 0;
          if (!in.golomb(kListCount, &nr) || !in.golomb(kListCount, &nm))
            return truncated("lists", i);
          if (nr > removed_total - r0 || nm > modified_total - m0)
            return bad_compact(string_printf("merge %u: lists beyond the header's", i));
          for (int list = 0; list < 2; ++list) {
            std::vector<uint32_t>& target = list == 0 ? h.removed : h.modified;
            for (uint64_t k = 0, n = list == 0 ? nr : nm; k < n; ++k) {
              if (!in.golomb(kTriangle, &value)) return truncated("lists", i);
              const int64_t t = previous_triangle + unzigzag64(value);
              if (t < 0 || t >= t_count)
                return bad_compact(string_printf("merge %u: triangle out of range", i));
              previous_triangle = t;
              target.push_back(static_cast<uint32_t>(t));
            }
          }
        }
        h.removed_start.push_back(static_cast<uint32_t>(h.removed.size()));
        h.modified_start.push_back(static_cast<uint32_t>(h.modified.size()));
        replay.collapse(u, centre, h.removed.data() + r0, h.removed.size() - r0,
                        h.modified.data() + m0, h.modified.size() - m0);
      }
      h.child_start.push_back(static_cast<uint32_t>(h.children.size()));
      top[centre] = v_count + i;
    }
    return finish_compact_decode(kFanhTag, in, encode_fanh(h), fixed, kFanhFixedBytes, "hierarchy");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact FANH");
  }
}

}  // namespace lodbake
