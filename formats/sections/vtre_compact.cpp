// Compact VTRE (codec 1): a lossless recoding of a raw VTRE payload, layout
// in docs/format.md "Compact VTRE". The trees of To, Lau & Green (2001)
// store each split's two fans explicitly; both are rearrangements of the
// split vertex's fan just before the split, which the decoder knows.
//
// Choices, measured on the Stanford bunny's balanced hierarchy (34834
// vertices, raw 305 bits per vertex, compact 119):
// - Every vertex keeps a *known fan*: its flattened fan as last stored,
//   then edited by later splits of its neighbours (a neighbour w of a new
//   vertex vt gets vt in place of vs when w left vs, next to vs when it is
//   a wing). It is not the exact current fan (that would need the mesh
//   replayed), only a prediction, capped at 64 entries so that hostile
//   input cannot make an edit cost more than a constant.
// - A fan of split k's nodes is coded against a candidate list and one
//   extra vertex it cannot hold: for the left node (vt) vs's known fan
//   and vs, for the right node (vs) that fan without the vertices the left
//   node took (its entries other than vs and the wings, vs's neighbours in
//   it) and vt. vs's old ring is vl, x.., vr, y..; vt's new one vl, x..,
//   vr, vs and vs's vl, vt, vr, y..: both keep the old clockwise order, so
//   the first entry is coded as its index and each next one as the signed
//   step from the entry after the previous one, most often 0, with symbols
//   for the extra vertex and for an escape to a plain id. Symbols are
//   ordered by frequency (step 0 first: 1 bit), since Exp-Golomb codes
//   small values shortest.
// - Base fans (the base mesh's, no prediction) as zigzag differences from
//   the previous entry, the first from the node's own vertex.
// - Coordinates stay bit-exact float32: the difference of each component's
//   bit pattern from a prediction, zigzag, Exp-Golomb (equal signs and
//   exponents leave only the mantissa difference): for vt the midpoint of
//   the wings, coded after the fans that name them (20.2 bits per
//   coordinate on the bunny, against 21.0 from vs, as the VSPL codec
//   found for quantized positions), for a base vertex the previous one's.
//   Lossless float32 costs what the mantissas' noise costs: about 60 of
//   VTRE's 119 bits per vertex.
// - The parent vertex stays a bits(B + k) index (QEM order makes vs
//   uniform, as the VSPL codec measured), the state one bit.
// - The decoder rebuilds the trees and writes them with the raw writer,
//   so its output obeys every VTRE rule; the encoder refuses raw payloads
//   the raw writer would not write byte for byte (the codec cannot store
//   other bit widths).
#include "formats/sections/vtre_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/vtre.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int {
  kBaseCoord,
  kLeftCoord,
  kRunCount,
  kBaseLength,
  kLeftLength,
  kRightLength,
  kFirstEntry,
  kNextEntry,
  kBaseEntry,
  kContextCount
};

constexpr size_t kMaxKnown = 64;

Status bad_compact(const std::string& detail) {
  return malformed_section(kVtreTag, "compact: " + detail);
}

// The known fans (see the file comment).
class KnownFans {
 public:
  explicit KnownFans(size_t vertices) : fans_(vertices) {}

  const std::vector<uint32_t>& of(uint32_t v) const { return fans_[v]; }

  void set(uint32_t v, const uint32_t* entries, size_t count) {
    fans_[v].assign(entries, entries + (count < kMaxKnown ? count : kMaxKnown));
  }

  // After split (vs -> vs, vt) with fans `left` (vt's) and `right` (vs's).
  void split(uint32_t vs, uint32_t vt, const uint32_t* left, size_t left_count,
             const uint32_t* right, size_t right_count) {
    set(vs, right, right_count);
    set(vt, left, left_count);
    // Only the first kMaxKnown entries of each fan: hostile fans of any
    // length then cost a constant per split.
    for (size_t i = 0; i < left_count && i < kMaxKnown; ++i) {
      const uint32_t w = left[i];
      if (w == vs) continue;
      bool wing = false;
      for (size_t j = 0; j < right_count && j < kMaxKnown && !wing; ++j)
        wing = right[j] == w;
      std::vector<uint32_t>& fan = fans_[w];
      size_t at = 0;
      while (at < fan.size() && fan[at] != vs)
        ++at;
      if (at < fan.size() && !wing) {
        fan[at] = vt;
      } else if (fan.size() < kMaxKnown) {
        fan.insert(fan.begin() + static_cast<ptrdiff_t>(at < fan.size() ? at + 1 : at), vt);
      }
    }
  }

 private:
  std::vector<std::vector<uint32_t>> fans_;
};

// Vertices that exist when node `node` appears (as in the raw codec).
uint64_t existing_at(uint64_t b, uint64_t node) {
  return node < b ? b : b + (node - b) / 2 + 1;
}

// The signed step from `expected` to `pos` in a cyclic list of m entries,
// the one of least magnitude (ties: the positive one).
int64_t cyclic_step(size_t pos, size_t expected, size_t m) {
  int64_t d = static_cast<int64_t>(pos) - static_cast<int64_t>(expected);
  const int64_t half = static_cast<int64_t>(m / 2);
  if (d > half) d -= static_cast<int64_t>(m);
  if (d < -half || (d == -half && m % 2 == 0 && half != 0)) d += static_cast<int64_t>(m);
  return d;
}

uint64_t coordinate_code(float value, float predicted) {
  return zigzag64(static_cast<int64_t>(float_bits(value)) -
                  static_cast<int64_t>(float_bits(predicted)));
}

constexpr uint32_t kNone = UINT32_MAX;

// The symbols of a split node's fan entries, most frequent first (the
// Exp-Golomb codes of small values are the shortest). First entry: the
// extra vertex, an escape, or kFirstIndex + its index. Next entries: step
// 0, the extra vertex, an escape, then the other steps by magnitude.
constexpr uint64_t kFirstExtra = 0, kFirstEscape = 1, kFirstIndex = 2;
constexpr uint64_t kNextStepZero = 0, kNextExtra = 1, kNextEscape = 2, kNextSteps = 3;

uint64_t next_code(int64_t step) {
  return step == 0 ? kNextStepZero : kNextSteps + zigzag64(step) - 1;
}
// \pre code is neither kNextExtra nor kNextEscape.
int64_t next_step(uint64_t code) {
  return code == kNextStepZero ? 0 : unzigzag64(code - kNextSteps + 1);
}

// The neighbours of vs in the left node's fan (vt's): the wings vl and vr
// of the split, as vs's ring neighbours in each run. \pre the left node's
// runs are complete in `t`.
void left_wings(const VertexTrees& t, size_t left, uint32_t vs, std::vector<uint32_t>* wings) {
  wings->clear();
  for (uint32_t r = t.run_offsets[left]; r < t.run_offsets[left + 1]; ++r) {
    const uint32_t a = t.vertex_offsets[r], z = t.vertex_offsets[r + 1];
    for (uint32_t j = a; j < z; ++j) {
      if (t.fan_vertices[j] != vs) continue;
      if (j > a || t.run_closed[r] != 0) wings->push_back(t.fan_vertices[j > a ? j - 1 : z - 1]);
      if (j + 1 < z || t.run_closed[r] != 0)
        wings->push_back(t.fan_vertices[j + 1 < z ? j + 1 : a]);
    }
  }
}

// The right node's candidates: vs's known fan without the vertices the
// left node took (its entries other than vs and the wings), which moved
// from vs to vt.
void right_candidates(const VertexTrees& t, size_t left, uint32_t vs,
                      const std::vector<uint32_t>& known, const std::vector<uint32_t>& wings,
                      std::vector<uint32_t>* out) {
  out->clear();
  const uint32_t a = t.vertex_offsets[t.run_offsets[left]];
  const uint32_t z = t.vertex_offsets[t.run_offsets[left + 1]];
  for (uint32_t x : known) {
    bool moved = false;
    for (uint32_t j = a; j < z && !moved; ++j)
      moved = t.fan_vertices[j] == x;
    for (uint32_t w : wings)
      moved = moved && w != x;
    if (!moved && x != vs) out->push_back(x);
  }
}

// The predicted coordinate of vt: the midpoint of two distinct wings, else
// vs's.
Vec3f left_prediction(const VertexTrees& t, uint32_t vs, const std::vector<uint32_t>& wings) {
  uint32_t first = kNone, second = kNone;
  for (uint32_t w : wings) {
    if (first == kNone) {
      first = w;
    } else if (w != first && second == kNone) {
      second = w;
    }
  }
  if (second == kNone) return t.positions[vs];
  Vec3f mid{};
  for (int a = 0; a < 3; ++a)
    mid[a] = 0.5f * (t.positions[first][a] + t.positions[second][a]);
  return mid;
}

// The encoder's walk over `t`.
void encode_pass(const VertexTrees& t, CompactStreamWriter* out) {
  const uint32_t b = t.base_vertex_count;
  KnownFans known(uint64_t{b} + t.split_count());
  std::vector<uint32_t> candidates, wings, known_fan;
  // `extra`: the one vertex of a split node's fan that its candidates
  // cannot hold (kNone for base nodes, which have no candidates).
  auto code_fan = [&](size_t node, int length_ctx, uint32_t own, uint32_t extra) {
    const uint32_t runs = t.run_offsets[node + 1] - t.run_offsets[node];
    out->golomb(kRunCount, zigzag64(int64_t{runs} - 1));
    const int escape_bits = bits_for_count(existing_at(b, node));
    const size_t m = candidates.size();
    int64_t previous = -1;  // position of the previous entry found, -1 before the first
    uint32_t last = own;
    for (uint32_t r = t.run_offsets[node]; r < t.run_offsets[node + 1]; ++r) {
      out->bits(t.run_closed[r], 1);
      out->golomb(length_ctx, t.vertex_offsets[r + 1] - t.vertex_offsets[r] - 2);
      for (uint32_t j = t.vertex_offsets[r]; j < t.vertex_offsets[r + 1]; ++j) {
        const uint32_t e = t.fan_vertices[j];
        if (extra == kNone) {
          out->golomb(kBaseEntry, zigzag64(int64_t{e} - int64_t{last}));
          last = e;
          continue;
        }
        const int ctx = previous < 0 ? kFirstEntry : kNextEntry;
        if (e == extra) {
          out->golomb(ctx, previous < 0 ? kFirstExtra : kNextExtra);
          continue;
        }
        const size_t expected = previous < 0 ? 0 : (static_cast<size_t>(previous) + 1) % m;
        int64_t best_step = 0;
        size_t best_pos = m;
        for (size_t p = 0; p < m; ++p) {
          if (candidates[p] != e) continue;
          const int64_t step = cyclic_step(p, expected, m);
          if (best_pos == m || zigzag64(step) < zigzag64(best_step)) {
            best_step = step;
            best_pos = p;
          }
        }
        if (best_pos == m) {
          out->golomb(ctx, previous < 0 ? kFirstEscape : kNextEscape);
          out->bits(e, escape_bits);
          continue;
        }
        out->golomb(ctx, previous < 0 ? kFirstIndex + best_pos : next_code(best_step));
        previous = static_cast<int64_t>(best_pos);
      }
    }
  };
  for (uint32_t v = 0; v < b; ++v) {
    for (int a = 0; a < 3; ++a)
      out->golomb(kBaseCoord,
                  coordinate_code(t.positions[v][a], v == 0 ? 0.0f : t.positions[v - 1][a]));
    out->bits(t.vertex_states[v], 1);
    candidates.clear();
    code_fan(v, kBaseLength, v, kNone);
    const uint32_t* fan = t.fan_vertices.data() + t.vertex_offsets[t.run_offsets[v]];
    known.set(v, fan, t.vertex_offsets[t.run_offsets[v + 1]] - t.vertex_offsets[t.run_offsets[v]]);
  }
  for (size_t k = 0; k < t.split_count(); ++k) {
    const uint32_t vs = t.parent_vertex[k];
    const uint32_t vt = static_cast<uint32_t>(b + k);
    const size_t left = b + 2 * k;
    out->bits(vs, bits_for_count(uint64_t{b} + k));
    out->bits(t.vertex_states[vt], 1);
    known_fan = known.of(vs);
    candidates = known_fan;
    code_fan(left, kLeftLength, vt, vs);
    left_wings(t, left, vs, &wings);
    right_candidates(t, left, vs, known_fan, wings, &candidates);
    code_fan(left + 1, kRightLength, vs, vt);
    const Vec3f predicted = left_prediction(t, vs, wings);
    for (int a = 0; a < 3; ++a)
      out->golomb(kLeftCoord, coordinate_code(t.positions[vt][a], predicted[a]));
    const uint32_t* fans = t.fan_vertices.data();
    const uint32_t l0 = t.vertex_offsets[t.run_offsets[left]];
    const uint32_t l1 = t.vertex_offsets[t.run_offsets[left + 1]];
    const uint32_t r1 = t.vertex_offsets[t.run_offsets[left + 2]];
    known.split(vs, vt, fans + l0, l1 - l0, fans + l1, r1 - l1);
  }
}

}  // namespace

Result<Bytes> encode_vtre_compact(const uint8_t* raw, size_t raw_size) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, decode_vtre(raw, raw_size));
    LODBAKE_ASSIGN_OR_RETURN(Bytes canonical, encode_vtre(trees));
    LODBAKE_RETURN_IF_ERROR(
        require_canonical_layout(kVtreTag, canonical, raw, raw_size, "bit widths"));
    // Sized first: push_back then a range insert trips g++ 12's -Warray-bounds.
    Bytes out(1 + kVtreFixedBytes);
    out[0] = kVtreCompactVersion;
    std::memcpy(out.data() + 1, raw, kVtreFixedBytes);
    CompactStreamWriter stream(kContextCount);
    encode_pass(trees, &stream);
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact VTRE");
  }
}

Result<Bytes> decode_vtre_compact(const uint8_t* data, size_t size) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kVtreTag, data, size, kVtreFixedBytes, kVtreCompactVersion));
    const uint8_t* fixed = data + 1;
    uint32_t b = 0, splits = 0, run_total = 0, fan_total = 0;
    std::memcpy(&b, fixed, 4);
    std::memcpy(&splits, fixed + 4, 4);
    std::memcpy(&run_total, fixed + 8, 4);
    std::memcpy(&fan_total, fixed + 12, 4);
    const uint64_t vertices = uint64_t{b} + splits;
    if (vertices > UINT32_MAX - 1) return bad_compact("more than 2^32 - 2 vertices");
    if (splits != 0 && b == 0) return bad_compact("splits without a base vertex");
    CompactStreamReader in;
    if (!in.start(fixed + kVtreFixedBytes, size - 1 - kVtreFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // Each coordinate code, node's run count, run and fan entry takes at
    // least one bit: this bounds every allocation below by the input size.
    const uint64_t nodes = uint64_t{b} + 2 * uint64_t{splits};
    const uint64_t min_bits = 3 * vertices + nodes + uint64_t{run_total} * 2 + fan_total;
    if (min_bits > in.bits_left()) {
      return bad_compact(string_printf("%" PRIu64 " vertices, %u runs and %u fan entries need at "
                                       "least %" PRIu64 " bits, %" PRIu64 " remain",
                                       vertices, run_total, fan_total, min_bits, in.bits_left()));
    }
    VertexTrees t;
    t.base_vertex_count = b;
    t.positions.resize(vertices);
    t.vertex_states.resize(vertices);
    t.parent_vertex.resize(splits);
    t.run_offsets.reserve(nodes + 1);
    t.run_closed.reserve(run_total);
    t.vertex_offsets.reserve(uint64_t{run_total} + 1);
    t.fan_vertices.reserve(fan_total);
    KnownFans known(vertices);
    std::vector<uint32_t> candidates, wings, known_fan;
    uint64_t value = 0;
    auto truncated = [](const char* what, uint64_t node) {
      return bad_compact(
          string_printf("truncated or malformed code in the %s of node %" PRIu64, what, node));
    };
    auto decode_fan = [&](uint64_t node, int length_ctx, uint32_t own, uint32_t extra) -> Status {
      if (!in.golomb(kRunCount, &value)) return truncated("run count", node);
      const int64_t runs = unzigzag64(value) + 1;
      if (runs < 0 || static_cast<uint64_t>(runs) > run_total - t.run_closed.size())
        return bad_compact(
            string_printf("node %" PRIu64 " has runs beyond the header's %u", node, run_total));
      const uint64_t existing = existing_at(b, node);
      const int escape_bits = bits_for_count(existing);
      const size_t m = candidates.size();
      int64_t previous = -1;
      uint32_t last = own;
      for (int64_t r = 0; r < runs; ++r) {
        uint64_t closed = 0;
        if (!in.bits(1, &closed)) return truncated("run closed bit", node);
        if (!in.golomb(length_ctx, &value)) return truncated("run length", node);
        if (value > fan_total - t.fan_vertices.size() ||
            value + 2 > fan_total - t.fan_vertices.size())
          return bad_compact(string_printf(
              "node %" PRIu64 " has fan entries beyond the header's %u", node, fan_total));
        const uint64_t length = value + 2;
        for (uint64_t j = 0; j < length; ++j) {
          uint64_t e = 0;
          if (extra == kNone) {
            if (!in.golomb(kBaseEntry, &value)) return truncated("fan", node);
            const int64_t id = int64_t{last} + unzigzag64(value);
            if (id < 0 || id > UINT32_MAX)
              return bad_compact(string_printf("node %" PRIu64 ": fan entry out of range", node));
            e = static_cast<uint64_t>(id);
            last = static_cast<uint32_t>(e);
          } else {
            const size_t expected = previous < 0 ? 0 : (static_cast<size_t>(previous) + 1) % m;
            if (!in.golomb(previous < 0 ? kFirstEntry : kNextEntry, &value))
              return truncated("fan", node);
            const bool first = previous < 0;
            if (value == (first ? kFirstEscape : kNextEscape)) {
              if (!in.bits(escape_bits, &e)) return truncated("fan", node);
            } else if (value == (first ? kFirstExtra : kNextExtra)) {
              e = extra;
            } else {
              int64_t pos = 0;
              if (first) {
                if (value - kFirstIndex >= m)
                  return bad_compact(string_printf("node %" PRIu64 ": fan index %" PRIu64
                                                   " past %zu known",
                                                   node, value - kFirstIndex, m));
                pos = static_cast<int64_t>(value - kFirstIndex);
              } else {
                if (m == 0)
                  return bad_compact(string_printf("node %" PRIu64 ": no known fan", node));
                const int64_t step = next_step(value);
                if (step > static_cast<int64_t>(m) || step < -static_cast<int64_t>(m))
                  return bad_compact(
                      string_printf("node %" PRIu64 ": fan step past %zu known", node, m));
                pos = (static_cast<int64_t>(expected) + step + 2 * static_cast<int64_t>(m)) %
                      static_cast<int64_t>(m);
              }
              e = candidates[static_cast<size_t>(pos)];
              previous = pos;
            }
          }
          // The known fans are indexed by entries: an id that does not exist
          // yet must stop here, before it reaches them.
          if (e >= existing)
            return bad_compact(string_printf(
                "node %" PRIu64 ": fan vertex %" PRIu64 " does not exist at that node", node, e));
          t.fan_vertices.push_back(static_cast<uint32_t>(e));
        }
        t.run_closed.push_back(static_cast<uint8_t>(closed));
        t.vertex_offsets.push_back(static_cast<uint32_t>(t.fan_vertices.size()));
      }
      t.run_offsets.push_back(static_cast<uint32_t>(t.run_closed.size()));
      return Status::ok();
    };
    auto coordinate = [&](int ctx, float predicted, float* out, uint64_t node) -> Status {
      if (!in.golomb(ctx, &value)) return truncated("coordinates", node);
      const int64_t pattern = int64_t{float_bits(predicted)} + unzigzag64(value);
      if (pattern < 0 || pattern > UINT32_MAX)
        return bad_compact(string_printf("node %" PRIu64 ": coordinate out of range", node));
      *out = bits_float(static_cast<uint32_t>(pattern));
      return Status::ok();
    };
    for (uint32_t v = 0; v < b; ++v) {
      for (int a = 0; a < 3; ++a) {
        LODBAKE_RETURN_IF_ERROR(
            coordinate(kBaseCoord, v == 0 ? 0.0f : t.positions[v - 1][a], &t.positions[v][a], v));
      }
      if (!in.bits(1, &value)) return truncated("state", v);
      t.vertex_states[v] = static_cast<uint8_t>(value);
      candidates.clear();
      const size_t start = t.fan_vertices.size();
      LODBAKE_RETURN_IF_ERROR(decode_fan(v, kBaseLength, v, kNone));
      known.set(v, t.fan_vertices.data() + start, t.fan_vertices.size() - start);
    }
    for (uint32_t k = 0; k < splits; ++k) {
      const uint64_t left = uint64_t{b} + 2 * uint64_t{k};
      const uint32_t vt = b + k;
      if (!in.bits(bits_for_count(uint64_t{b} + k), &value)) return truncated("parent", left);
      if (value >= uint64_t{b} + k)
        return bad_compact(
            string_printf("split %u: parent vertex %" PRIu64 " does not exist yet", k, value));
      const uint32_t vs = static_cast<uint32_t>(value);
      t.parent_vertex[k] = vs;
      if (!in.bits(1, &value)) return truncated("state", left);
      t.vertex_states[vt] = static_cast<uint8_t>(value);
      known_fan = known.of(vs);
      candidates = known_fan;
      const size_t l0 = t.fan_vertices.size();
      LODBAKE_RETURN_IF_ERROR(decode_fan(left, kLeftLength, vt, vs));
      left_wings(t, left, vs, &wings);
      right_candidates(t, left, vs, known_fan, wings, &candidates);
      const size_t l1 = t.fan_vertices.size();
      LODBAKE_RETURN_IF_ERROR(decode_fan(left + 1, kRightLength, vs, vt));
      const Vec3f predicted = left_prediction(t, vs, wings);
      for (int a = 0; a < 3; ++a) {
        LODBAKE_RETURN_IF_ERROR(coordinate(kLeftCoord, predicted[a], &t.positions[vt][a], left));
      }
      const uint32_t* fans = t.fan_vertices.data();
      known.split(vs, vt, fans + l0, l1 - l0, fans + l1, t.fan_vertices.size() - l1);
    }
    return finish_compact_decode(kVtreTag, in, encode_vtre(t), fixed, kVtreFixedBytes, "trees");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact VTRE");
  }
}

}  // namespace lodbake
