// Compact WEDG (codec 1): a lossless recoding of a raw WEDG payload against
// its BASE, layout in docs/format.md "Compact WEDG". Raw WEDG spends 4
// bytes on every wedge number; most of them are implied by the progressive
// mesh: a corner at vertex v uses one of v's wedges (the wedges whose home
// is v), and most vertices have one.
//
// Choices, measured on Duck (2399 wedges, 1888 splits, 6352 moved corners,
// raw 112312 bytes), CesiumMilkTruck's two meshes and SheenCloth:
// - Corners at a known vertex (BASE's corners, each split's corners at vt =
//   B + i, the moved corners at vt): the rank among the vertex's wedges,
//   coded only when the vertex has more than one, and counted from a
//   reference wedge of the same split (the first vt corner; for the second
//   vs corner, the first), since a split's corners at one vertex mostly
//   share a wedge. Every corner of the three assets is at its wedge's home;
//   a mode bit adds an escape for payloads where some are not (a seam moved
//   by a --permissive collapse).
// - The first vs corner as the difference from the first vt corner's
//   wedge (the wedge table follows the input's triangles, so neighbours
//   are numbered close: 8.2 bits on Duck), the vl and vr corners as
//   differences from the vs corner of their face (9.0 and 9.1; from the vt
//   corner 9.3 and 9.3).
// - The wedge table: primitives as runs; each vertex against the largest
//   of its primitive so far plus one (wedges are met in the input's vertex
//   order: 2399 of 2399 on Duck); the home by kind: a removed vertex not
//   used yet (rank among those, in bits(unused) bits: 9.9 bits against
//   11.8 for the difference from the previous home), a copy of an earlier
//   wedge's home (a seam), the next base vertex (base vertices keep the
//   input's order), or explicit.
// - Exp-Golomb streams (compact_coding.h), as the codecs other than VSPL's,
//   so a count is bounded by the bits before allocating (each wedge and
//   each split takes at least one); the moved corners, mostly free, by a
//   stated limit of 8 per bit. Ranks cost nothing where a vertex has one
//   wedge, so an adaptive range coder would gain little but the flags.
#include "formats/sections/wedg_compact.h"

#include <algorithm>
#include <cinttypes>
#include <cstring>
#include <map>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/wedg.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int {
  kPrimitive,   // zigzag(a run's primitive - the previous run's)
  kRunLength,   // a run's wedges - 1
  kVertex,      // zigzag(vertex - the primitive's largest so far - 1)
  kHomeKind,    // HomeKind
  kHomeCopy,    // wedges back to the one whose home is copied, - 1
  kHomeOther,   // zigzag(home - next base)
  kBaseRank,    // a BASE corner's wedge
  kWings,       // 0 both, 1 left only, 2 right only, 3 none
  kVtRank,      // an added face's corner at vt
  kVsDelta,     // zigzag(first vs corner - first vt corner)
  kVsRank,      // the second vs corner, from the first
  kLeftDelta,   // zigzag(vl corner - vs corner)
  kRightDelta,  // zigzag(vr corner - vs corner)
  kMovedCount,  // faces moved by the split
  kMovedRank,   // a moved corner at vt, from the first vt corner
  kEscape,      // zigzag(wedge - reference or 0), after rank = n
  kContextCount
};

enum HomeKind : uint64_t { kRemoved = 0, kCopy = 1, kNextBase = 2, kOther = 3 };

// Mode bit: some corner is not at its wedge's home, so ranks have an escape.
constexpr uint8_t kModeEscapes = 1;
// The most moved corners a stream may hold per bit.
constexpr uint64_t kMovedPerBit = 8;
// version, the raw payload's fixed fields, mode.
constexpr size_t kHeaderBytes = 1 + kWedgFixedBytes + 1;

Status bad_compact(const std::string& detail) {
  return malformed_section(kWedgTag, "compact: " + detail);
}

// bits(n) of docs/format.md section 11: the width of values 0 .. n - 1.
int width_for(uint64_t n) {
  return n <= 1 ? 0 : bit_length(n - 1);
}

// The removed vertices (homes B .. B + S - 1) no wedge has taken yet, as a
// Fenwick tree of 0/1 flags: rank and select in O(log S).
class UnusedIds {
 public:
  explicit UnusedIds(size_t n) : flags_(n, 1), tree_(n + 1, 0), count_(n) {
    for (size_t i = 1; i <= n; ++i) {
      tree_[i] += 1;
      const size_t parent = i + (i & (~i + 1));
      if (parent <= n) tree_[parent] += tree_[i];
    }
    while (top_ * 2 <= n)
      top_ *= 2;
  }
  size_t count() const { return count_; }
  bool contains(size_t i) const { return flags_[i] != 0; }
  // Unused ids below i.
  size_t rank(size_t i) const {
    size_t sum = 0;
    for (size_t k = i; k > 0; k -= k & (~k + 1))
      sum += tree_[k];
    return sum;
  }
  // The unused id of rank r. \pre r < count().
  size_t select(size_t r) const {
    size_t at = 0;
    for (size_t step = top_; step > 0; step /= 2) {
      if (at + step < tree_.size() && tree_[at + step] <= r) {
        at += step;
        r -= tree_[at];
      }
    }
    return at;
  }
  void erase(size_t i) {
    flags_[i] = 0;
    --count_;
    for (size_t k = i + 1; k < tree_.size(); k += k & (~k + 1))
      --tree_[k];
  }

 private:
  std::vector<uint8_t> flags_;
  std::vector<uint32_t> tree_;
  size_t count_;
  size_t top_ = 1;
};

// What the wedge table's coding predicts from, the same on both sides.
struct TableState {
  TableState(uint32_t base, uint32_t splits) : base_vertices(base), unused(splits) {}
  uint64_t predicted_vertex(uint32_t primitive) const {
    auto it = next_vertex.find(primitive);
    return it == next_vertex.end() ? 0 : it->second;
  }
  void took(uint32_t primitive, uint32_t vertex, uint32_t home) {
    uint64_t& next = next_vertex[primitive];
    next = std::max<uint64_t>(next, uint64_t{vertex} + 1);
    if (home < base_vertices) {
      next_base = std::max<uint64_t>(next_base, uint64_t{home} + 1);
    } else if (unused.contains(home - base_vertices)) {
      unused.erase(home - base_vertices);
    }
  }
  uint32_t base_vertices;
  uint64_t next_base = 0;
  UnusedIds unused;
  std::map<uint32_t, uint64_t> next_vertex;  // per primitive, its largest vertex + 1
};

// Per vertex, the wedges whose home it is, in increasing order; per wedge,
// its rank in its home's list.
struct HomeLists {
  HomeLists(const std::vector<uint32_t>& home, size_t vertices)
      : offset(vertices + 1, 0), wedges(home.size()), position(home.size()) {
    for (uint32_t h : home)
      ++offset[h + 1];
    for (size_t v = 0; v < vertices; ++v)
      offset[v + 1] += offset[v];
    std::vector<uint32_t> fill(offset.begin(), offset.end() - 1);
    for (size_t w = 0; w < home.size(); ++w) {
      position[w] = fill[home[w]] - offset[home[w]];
      wedges[fill[home[w]]++] = static_cast<uint32_t>(w);
    }
  }
  uint32_t size(uint32_t v) const { return offset[v + 1] - offset[v]; }
  std::vector<uint32_t> offset;
  std::vector<uint32_t> wedges;
  std::vector<uint32_t> position;
};

// The corner coding both sides share: a corner at vertex v whose wedge is
// `ref`'s list mate is coded as its rank counted from ref's.
uint32_t reference_rank(const std::vector<uint32_t>& home, const HomeLists& lists, uint32_t v,
                        uint32_t ref) {
  return ref != kNoVertex && home[ref] == v ? lists.position[ref] : 0;
}

// ---- encoder ----

struct Encoder {
  const PmWedges& x;
  const TriangleMesh& base;
  const HomeLists& lists;
  bool escapes;
  CompactStreamWriter* out;

  void corner(int ctx, uint32_t v, uint32_t w, uint32_t ref) {
    const uint32_t n = lists.size(v);
    if (x.wedge_home[w] == v) {
      const uint32_t q = reference_rank(x.wedge_home, lists, v, ref);
      if (escapes || n > 1) out->golomb(ctx, (lists.position[w] + n - q) % n);
      return;
    }
    out->golomb(ctx, n);
    out->golomb(kEscape, zigzag64(int64_t{w} - (ref == kNoVertex ? 0 : int64_t{ref})));
  }

  void table() {
    const size_t count = x.wedge_count();
    int64_t previous = 0;
    for (size_t a = 0; a < count;) {
      size_t z = a + 1;
      while (z < count && x.wedge_primitive[z] == x.wedge_primitive[a])
        ++z;
      out->golomb(kPrimitive, zigzag64(int64_t{x.wedge_primitive[a]} - previous));
      out->golomb(kRunLength, z - a - 1);
      previous = x.wedge_primitive[a];
      a = z;
    }
    TableState state(static_cast<uint32_t>(base.positions.size()),
                     static_cast<uint32_t>(x.added.size()));
    std::vector<uint32_t> last(lists.offset.size() - 1, kNoVertex);  // per home, its last wedge
    for (size_t w = 0; w < count; ++w) {
      const uint32_t p = x.wedge_primitive[w], h = x.wedge_home[w];
      out->golomb(kVertex, zigzag64(static_cast<int64_t>(x.wedge_vertex[w]) -
                                    static_cast<int64_t>(state.predicted_vertex(p))));
      const uint32_t b = state.base_vertices;
      if (h >= b && state.unused.contains(h - b)) {
        out->golomb(kHomeKind, kRemoved);
        out->bits(state.unused.rank(h - b), width_for(state.unused.count()));
      } else if (last[h] != kNoVertex) {
        out->golomb(kHomeKind, kCopy);
        out->golomb(kHomeCopy, w - last[h] - 1);
      } else if (h == state.next_base) {
        out->golomb(kHomeKind, kNextBase);
      } else {
        out->golomb(kHomeKind, kOther);
        out->golomb(kHomeOther, zigzag64(int64_t{h} - static_cast<int64_t>(state.next_base)));
      }
      state.took(p, x.wedge_vertex[w], h);
      last[h] = static_cast<uint32_t>(w);
    }
  }

  void corners() {
    for (size_t t = 0; t < x.base.size(); ++t)
      for (int k = 0; k < 3; ++k)
        corner(kBaseRank, base.triangles[t][k], x.base[t][k], kNoVertex);
    const uint32_t b = static_cast<uint32_t>(base.positions.size());
    for (size_t i = 0; i < x.added.size(); ++i) {
      const std::array<uint32_t, 6>& a = x.added[i];
      const uint32_t vt = b + static_cast<uint32_t>(i);
      const bool left = a[0] != kNoVertex, right = a[3] != kNoVertex;
      out->golomb(kWings, (left ? 0 : 2) + (right ? 0 : 1));
      if (left) corner(kVtRank, vt, a[1], kNoVertex);
      if (right) corner(kVtRank, vt, a[3], left ? a[1] : kNoVertex);
      const uint32_t first_vt = left ? a[1] : right ? a[3] : kNoVertex;
      if (left) out->golomb(kVsDelta, zigzag64(int64_t{a[0]} - first_vt));
      if (right && left) corner(kVsRank, x.wedge_home[a[0]], a[4], a[0]);
      if (right && !left) out->golomb(kVsDelta, zigzag64(int64_t{a[4]} - first_vt));
      if (left) out->golomb(kLeftDelta, zigzag64(int64_t{a[2]} - a[0]));
      if (right) out->golomb(kRightDelta, zigzag64(int64_t{a[5]} - a[4]));
      out->golomb(kMovedCount, x.moved_offset[i + 1] - x.moved_offset[i]);
      for (uint32_t k = x.moved_offset[i]; k < x.moved_offset[i + 1]; ++k)
        corner(kMovedRank, vt, x.moved[k], first_vt);
    }
  }
};

// True when some corner is not at the vertex the codec names it by.
bool needs_escapes(const PmWedges& x, const TriangleMesh& base) {
  const std::vector<uint32_t>& home = x.wedge_home;
  for (size_t t = 0; t < x.base.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (home[x.base[t][k]] != base.triangles[t][k]) return true;
  const uint32_t b = static_cast<uint32_t>(base.positions.size());
  for (size_t i = 0; i < x.added.size(); ++i) {
    const std::array<uint32_t, 6>& a = x.added[i];
    const uint32_t vt = b + static_cast<uint32_t>(i);
    if (a[0] != kNoVertex && home[a[1]] != vt) return true;
    if (a[3] != kNoVertex && home[a[3]] != vt) return true;
    if (a[0] != kNoVertex && a[3] != kNoVertex && home[a[4]] != home[a[0]]) return true;
    for (uint32_t k = x.moved_offset[i]; k < x.moved_offset[i + 1]; ++k)
      if (home[x.moved[k]] != vt) return true;
  }
  return false;
}

// ---- decoder ----

struct Decoder {
  CompactStreamReader* in;
  const TriangleMesh& base;
  bool escapes;
  PmWedges x;

  Status read(int ctx, uint64_t* value, const char* what) {
    if (!in->golomb(ctx, value)) return bad_compact(std::string("truncated or malformed ") + what);
    return Status::ok();
  }

  // A wedge number `reference` + zigzag-decoded difference, below W.
  Status read_delta(int ctx, int64_t reference, uint32_t* w, const char* what) {
    uint64_t code = 0;
    LODBAKE_RETURN_IF_ERROR(read(ctx, &code, what));
    const int64_t value = reference + unzigzag64(code);
    if (value < 0 || static_cast<uint64_t>(value) >= x.wedge_count())
      return bad_compact(string_printf("%s %" PRId64 " is out of range", what, value));
    *w = static_cast<uint32_t>(value);
    return Status::ok();
  }

  Status corner(const HomeLists& lists, int ctx, uint32_t v, uint32_t ref, uint32_t* w,
                const char* what) {
    const uint32_t n = lists.size(v);
    uint64_t r = 0;
    if (escapes || n > 1) {
      LODBAKE_RETURN_IF_ERROR(read(ctx, &r, what));
    } else if (n == 0) {
      return bad_compact(string_printf("%s: vertex %u has no wedge", what, v));
    }
    if (r > n || (r == n && !escapes))
      return bad_compact(string_printf("%s: rank %" PRIu64 " of %u wedges", what, r, n));
    if (r == n) return read_delta(kEscape, ref == kNoVertex ? 0 : int64_t{ref}, w, what);
    const uint32_t q = reference_rank(x.wedge_home, lists, v, ref);
    *w = lists.wedges[lists.offset[v] + (static_cast<uint32_t>(r) + q) % n];
    return Status::ok();
  }

  Status table(uint32_t wedges, uint32_t splits) {
    x.wedge_primitive.reserve(wedges);
    uint64_t code = 0;
    int64_t previous = 0;
    while (x.wedge_primitive.size() < wedges) {
      LODBAKE_RETURN_IF_ERROR(read(kPrimitive, &code, "primitive"));
      const int64_t p = previous + unzigzag64(code);
      if (p < 0 || p > UINT32_MAX) return bad_compact("a primitive out of range");
      LODBAKE_RETURN_IF_ERROR(read(kRunLength, &code, "run length"));
      if (code >= wedges - x.wedge_primitive.size())
        return bad_compact("a primitive's run passes the wedge count");
      x.wedge_primitive.insert(x.wedge_primitive.end(), code + 1, static_cast<uint32_t>(p));
      previous = p;
    }
    const uint32_t b = static_cast<uint32_t>(base.positions.size());
    TableState state(b, splits);
    x.wedge_vertex.resize(wedges);
    x.wedge_home.resize(wedges);
    for (uint32_t w = 0; w < wedges; ++w) {
      const uint32_t p = x.wedge_primitive[w];
      LODBAKE_RETURN_IF_ERROR(read(kVertex, &code, "vertex"));
      const int64_t v = static_cast<int64_t>(state.predicted_vertex(p)) + unzigzag64(code);
      if (v < 0 || v > UINT32_MAX)
        return bad_compact(string_printf("wedge %u: vertex out of range", w));
      uint64_t kind = 0;
      LODBAKE_RETURN_IF_ERROR(read(kHomeKind, &kind, "home kind"));
      int64_t h = 0;
      if (kind == kRemoved) {
        const size_t unused = state.unused.count();
        if (unused == 0) return bad_compact(string_printf("wedge %u: no removed vertex left", w));
        uint64_t r = 0;
        if (!in->bits(width_for(unused), &r) || r >= unused)
          return bad_compact(string_printf("wedge %u: truncated or out-of-range home", w));
        h = b + static_cast<int64_t>(state.unused.select(static_cast<size_t>(r)));
      } else if (kind == kCopy) {
        LODBAKE_RETURN_IF_ERROR(read(kHomeCopy, &code, "home copy"));
        if (code >= w) return bad_compact(string_printf("wedge %u copies a later home", w));
        h = x.wedge_home[w - 1 - code];
      } else if (kind == kNextBase) {
        h = static_cast<int64_t>(state.next_base);
        if (h >= b) return bad_compact(string_printf("wedge %u: no base vertex left", w));
      } else if (kind == kOther) {
        LODBAKE_RETURN_IF_ERROR(read(kHomeOther, &code, "home"));
        h = static_cast<int64_t>(state.next_base) + unzigzag64(code);
        if (h < 0 || h >= int64_t{b} + splits)
          return bad_compact(string_printf("wedge %u: home out of range", w));
      } else {
        return bad_compact(string_printf("wedge %u: unknown home kind %" PRIu64, w, kind));
      }
      x.wedge_vertex[w] = static_cast<uint32_t>(v);
      x.wedge_home[w] = static_cast<uint32_t>(h);
      state.took(p, x.wedge_vertex[w], x.wedge_home[w]);
    }
    return Status::ok();
  }

  Status corners(uint32_t splits, uint32_t moved) {
    const uint32_t b = static_cast<uint32_t>(base.positions.size());
    const HomeLists lists(x.wedge_home, size_t{b} + splits);
    x.base.resize(base.triangles.size());
    for (size_t t = 0; t < x.base.size(); ++t)
      for (int k = 0; k < 3; ++k)
        LODBAKE_RETURN_IF_ERROR(corner(lists, kBaseRank, base.triangles[t][k], kNoVertex,
                                       &x.base[t][k], "base corner"));
    x.added.resize(splits);
    x.moved_offset.reserve(size_t{splits} + 1);
    x.moved_offset.push_back(0);
    uint64_t code = 0;
    for (uint32_t i = 0; i < splits; ++i) {
      std::array<uint32_t, 6>& a = x.added[i];
      a.fill(kNoVertex);
      const uint32_t vt = b + i;
      LODBAKE_RETURN_IF_ERROR(read(kWings, &code, "wings"));
      if (code > 3) return bad_compact(string_printf("split %u: wings %" PRIu64, i, code));
      const bool left = (code & 2) == 0, right = (code & 1) == 0;
      if (left) LODBAKE_RETURN_IF_ERROR(corner(lists, kVtRank, vt, kNoVertex, &a[1], "vt corner"));
      if (right)
        LODBAKE_RETURN_IF_ERROR(
            corner(lists, kVtRank, vt, left ? a[1] : kNoVertex, &a[3], "vt corner"));
      const uint32_t first_vt = left ? a[1] : right ? a[3] : kNoVertex;
      if (left) LODBAKE_RETURN_IF_ERROR(read_delta(kVsDelta, first_vt, &a[0], "vs corner"));
      if (right && left)
        LODBAKE_RETURN_IF_ERROR(
            corner(lists, kVsRank, x.wedge_home[a[0]], a[0], &a[4], "vs corner"));
      if (right && !left)
        LODBAKE_RETURN_IF_ERROR(read_delta(kVsDelta, first_vt, &a[4], "vs corner"));
      if (left) LODBAKE_RETURN_IF_ERROR(read_delta(kLeftDelta, a[0], &a[2], "vl corner"));
      if (right) LODBAKE_RETURN_IF_ERROR(read_delta(kRightDelta, a[4], &a[5], "vr corner"));
      LODBAKE_RETURN_IF_ERROR(read(kMovedCount, &code, "moved count"));
      if (code > moved - x.moved.size())
        return bad_compact(string_printf("split %u's moved corners pass the %u stored", i, moved));
      for (uint64_t k = 0; k < code; ++k) {
        uint32_t w = 0;
        LODBAKE_RETURN_IF_ERROR(corner(lists, kMovedRank, vt, first_vt, &w, "moved corner"));
        x.moved.push_back(w);
      }
      x.moved_offset.push_back(static_cast<uint32_t>(x.moved.size()));
    }
    if (x.moved.size() != moved)
      return bad_compact(
          string_printf("the splits move %zu corners, %u are stored", x.moved.size(), moved));
    return Status::ok();
  }
};

struct Counts {
  uint32_t flags, wedges, base, splits, moved;
};

Counts read_counts(const uint8_t* fixed) {
  Counts c{};
  std::memcpy(&c.flags, fixed, 4);
  std::memcpy(&c.wedges, fixed + 4, 4);
  std::memcpy(&c.base, fixed + 8, 4);
  std::memcpy(&c.splits, fixed + 12, 4);
  std::memcpy(&c.moved, fixed + 16, 4);
  return c;
}

}  // namespace

Result<Bytes> encode_wedg_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(PmWedges x, decode_wedg(raw, raw_size));
    if (x.base.size() != base.triangles.size()) {
      return unsupported(string_printf("WEDG names %zu base triangles, BASE has %zu", x.base.size(),
                                       base.triangles.size()));
    }
    const uint64_t vertices = uint64_t{base.positions.size()} + x.added.size();
    if (vertices >= kNoVertex) return unsupported("BASE's vertices and the splits pass 2^32 - 1");
    for (uint32_t h : x.wedge_home)
      if (h >= vertices)
        return unsupported(string_printf("a wedge's home %u is not one of the %" PRIu64
                                         " vertices of BASE and the splits",
                                         h, vertices));
    for (const Triangle& t : base.triangles)
      for (uint32_t v : t)
        if (v >= base.positions.size()) return invalid_input("a BASE triangle is out of range");
    const HomeLists lists(x.wedge_home, static_cast<size_t>(vertices));
    const bool escapes = needs_escapes(x, base);
    Bytes out(kHeaderBytes);
    out[0] = kWedgCompactVersion;
    std::memcpy(out.data() + 1, raw, kWedgFixedBytes);
    out[kHeaderBytes - 1] = escapes ? kModeEscapes : 0;
    CompactStreamWriter stream(kContextCount);
    Encoder encoder{x, base, lists, escapes, &stream};
    encoder.table();
    encoder.corners();
    const size_t stream_start = out.size() + kContextCount;  // after the order bytes
    stream.write_to(&out);
    if (x.moved.size() > kMovedPerBit * 8 * uint64_t{out.size() - stream_start})
      return unsupported("more moved corners than the compact stream can bound");
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact WEDG");
  }
}

Result<Bytes> decode_wedg_compact(const uint8_t* data, size_t size, const TriangleMesh& base) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kWedgTag, data, size, kWedgFixedBytes + 1, kWedgCompactVersion));
    const uint8_t* fixed = data + 1;
    const Counts c = read_counts(fixed);
    const uint8_t mode = data[kHeaderBytes - 1];
    if ((mode & ~kModeEscapes) != 0) return bad_compact(string_printf("unknown mode %u", mode));
    if (c.base != base.triangles.size()) {
      return bad_compact(
          string_printf("%u base triangles, BASE has %zu", c.base, base.triangles.size()));
    }
    if (uint64_t{base.positions.size()} + c.splits >= kNoVertex)
      return bad_compact("BASE's vertices and the splits pass 2^32 - 1");
    for (const Triangle& t : base.triangles)
      for (uint32_t v : t)
        if (v >= base.positions.size()) return bad_compact("a BASE triangle is out of range");
    CompactStreamReader in;
    if (!in.start(data + kHeaderBytes, size - kHeaderBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // Each wedge's vertex and each split's moved count take at least a bit;
    // moved corners are bounded by the stated limit.
    const uint64_t bits = in.bits_left();
    if (uint64_t{c.wedges} + c.splits > bits || c.moved > kMovedPerBit * bits) {
      return bad_compact(
          string_printf("%u wedges, %u splits and %u moved corners do not fit in %" PRIu64 " bits",
                        c.wedges, c.splits, c.moved, bits));
    }
    Decoder decoder{&in, base, (mode & kModeEscapes) != 0, {}};
    LODBAKE_RETURN_IF_ERROR(decoder.table(c.wedges, c.splits));
    LODBAKE_RETURN_IF_ERROR(decoder.corners(c.splits, c.moved));
    return finish_compact_decode(kWedgTag, in, encode_wedg(decoder.x), fixed, kWedgFixedBytes,
                                 "wedges");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact WEDG");
  }
}

}  // namespace lodbake
