// Compact VSPL (codec 1): a lossless recoding of a raw VSPL payload, layout
// in docs/format.md "Compact VSPL". Progressive-mesh coding after Hoppe
// 1996 ("Progressive meshes", section 5: vs as an index, wings by their
// place around vs, positions predicted from the neighbourhood) and Hoppe
// 1998 ("Efficient implementation of progressive meshes": the wings as a
// fan offset), entropy coded with the LZMA range coder
// (formats/support/range_coder.h).
//
// Layout version 4 (written when every error's bit pattern has zero low
// bits, i.e. after `lodbake-pack --error-bits`): version 3 with one byte,
// the number S of those bits, and each error coded as version 3 codes it
// but on its pattern shifted right by S. Exact errors keep their low
// mantissa bits, which are noise to every model tried (below); rounded up
// to 8 significant bits (S = 16), the errors of a pass, coded in
// decreasing cost order, differ by 0 or a unit most of the time: 13.74 ->
// 0.56 bits per split on the bunny (armadillo 13.68 -> 0.50, dragon
// 11.49 -> 0.26). The decoder refuses a shift smaller than the errors'
// common one, so that each raw payload has one version-4 encoding.
//
// Layout version 3 (written by default for exact errors), measured like version 2 below
// (bunny; armadillo and dragon in docs/benchmarks.md); it changes three
// parts and keeps the rest of version 2:
// - vs by its degree (its fan size, kept from what each record already
//   knows, capped at 15): a half-edge collapse leaves vs with the fans of
//   vs and vt together, so the vertices split next have large fans (the
//   bunny's vs mostly 7 or 8, its vertices mostly 6). The degree class is
//   coded adaptively, then vs's rank among the class's ids (by 16ths,
//   adaptive per class, which keeps version 2's "rarely a young vertex"),
//   from order-statistic sets: 13.22 -> 12.55 (armadillo 12.86 -> 12.45,
//   dragon 16.83 -> 16.55, whose irregular scan has broad degrees). 64ths
//   of the class instead of 16ths, the previous vs's class as context, the
//   degree against the neighbours' mean degree, or a class by the fan's
//   mean edge length as well: within 0.03. Ranking by last use (vs, vt or
//   wing) instead of by id: 0.3 worse.
// - vt from the fan's centroid c plus 26/64 (vs - c), -6/64 (wings'
//   midpoint - c) and 12/64 (moved vertices' centroid - c): the weights of
//   a least-squares fit (bunny and armadillo agree within 1/64; the
//   dragon's fit has -2/64 for the wings; weights 1 to 4/64 off cost the
//   bunny and armadillo 0.01 to 0.07), stored in the payload;
//   "vs twice" was the valence-dependent special case: 21.00 -> 20.71
//   (armadillo 22.64 -> 22.17). The last axis takes the fan's mean height
//   above the plane as context instead of its spread: 20.57 (22.13). Also
//   tried: the multi-parallelogram across the fan's edges (alone 1.8
//   worse; as a fourth weight 0.25 better but a fan walk per edge; its
//   height above the plane as correction or sign context, worse); the
//   polygon's area or perimeter centroid (worse); shearing the second
//   tangent axis along vs's direction (worse); the error as a position
//   context, coding it first (worse: dilution, no shared information);
//   3 or 4 adaptive mantissa bits (same).
// - The permutation by ranks: a valid permutation's next id is one of the
//   unused ones, so its rank among them is coded against the prediction's
//   rank (same median prediction and contexts): 9.93 -> 9.08 (armadillo
//   11.88 -> 10.62, dragon 8.78 -> 7.76). Predicting from the nearest fan
//   id with its index, the mean or a trimmed mean: worse than the median.
// Not changed: the errors (the largest of the last 4 differences' lengths
// as context: 0.05 better on the bunny and armadillo, 0.02 worse on the
// dragon), the wings.
// Decoding is 12-15% slower than version 2 (the class and rank sets).
// Speed is memory-bound: the records' vertices are scattered over arrays
// larger than the caches. Face lists in one cache line each, prefetching
// a record's ring, and in the writer prefetching the next records' fans
// took the dragon (436k splits, fastest of 15) from 1.44 to 1.25 s to
// decode and from 1.46 to 1.07 s to encode, the bunny from 0.080 to 0.072
// and 0.081 to 0.071 s.
//
// Layout version 2, measured on the Stanford bunny's full PM (34780 splits,
// 14-bit positions; bits per split; each step with LZMA's 11-bit
// probabilities, whose 16-bit replacement then took 0.3 bit more off:
// 63.3 in all, against 88 for version 1; 62.6 with the permutation below):
// - vs: uniform over n costs log2 n (13.66 against bits(n)'s 16); vs is
//   rarely a vertex created in the last quarter of the splits (bins of
//   vs / n have an entropy of 4.65 bits out of 5), so its 64th of [0, n) is
//   coded adaptively: 13.22. Neither the previous vs nor recent splits'
//   vertices predict it (a vs is among the last 64 records' vertices in
//   0.07% of the splits).
// - Wings: the connectivity is replayed (formats/mesh/split_connectivity.h),
//   vl is coded by its index in vs's current fan and vr by its offset back
//   from vl (the faces that move), adaptive per fan size and closedness:
//   4.74, against 17.8 for version 1's known-neighbour lists. Every wing of
//   a real PM is in its fan. A quantized closed fan starts at its vertex
//   farthest from vs (the moved faces were vt's, so far vertices lie between
//   vr and vl), which puts vl a step or two after the start: added last,
//   4.61 -> 4.14 (armadillo 4.82 -> 4.42).
// - Positions (quantized): vt from the centroid of its fan after the split
//   (22.63, against 24.76 from the wings' midpoint of version 1; weighting
//   the midpoint in, or leaving vs out, was worse; counting vs twice, added
//   last, took 0.05 more off, 0.47 on the armadillo), residual contexts by the
//   spread of the fan along each axis (22.11), and the axis most aligned
//   with the fan's Newell normal coded last, predicted on the tangent plane
//   from the other two residuals (21.27). Conditioning the last axis on the
//   first two residuals, or adapting faster (1/16), gained nothing; on
//   whether the fan's normal points down that axis (the side of the plane a
//   convex fan puts vt on), 0.07 (added last); a running mean of the last
//   axis's residual per context (JPEG-LS's bias cancellation), nothing.
// - Errors (float32, exact): the signed difference of each error's bit
//   pattern from the previous one, in the context of the previous
//   difference's size: 13.75 (version 1's Exp-Golomb: 13.8). Collapse costs are not
//   monotone, but neighbours in the order share exponent bits. The previous
//   error's exponent as context instead: 0.05 bit less on the bunny, 0.08
//   on the armadillo, 0.03 more on the dragon, so not kept.
// - Permutation: each split vertex's input id, coded with its record,
//   predicted by the median of its fan's input ids (vt's neighbours in the
//   full mesh, which input files number close together), in the context
//   of the fan's spread of ids: 9.93 per vertex (with 16-bit
//   probabilities), against bits(F) = 16 verbatim; from vs's id with the
//   wings' spread as context 10.58, the parallelogram vl + vr - vs in id
//   space 11.59.
// - Float32 positions, normals and texture coordinates are copied: they
//   cannot be predicted losslessly without a float residual coder, and
//   packing quantizes positions on request.
// - Adaptive models need a few hundred splits to learn: on the 31-split
//   golden grid version 2 is larger than version 1, so the writer keeps the
//   smaller of the two.
//
// Layout version 1 (read, and written when smaller): vs in bits(n), wings
// by their index in lists of vertices each vertex is known to neighbour
// (the base mesh's edges, then every split's new edges, capped at 64),
// positions predicted from the wings' midpoint, Exp-Golomb codes with the
// best order per part, the permutation verbatim.
#include "formats/sections/vspl_compact.h"

#include <algorithm>
#include <cinttypes>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/split_connectivity.h"
#include "formats/sections/vspl.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/exp_golomb.h"
#include "formats/support/quantization.h"
#include "formats/support/range_coder.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

constexpr size_t kMaxNeighbours = 64;
constexpr int kMaxGolombOrder = 32;
constexpr int kMaxGolombPrefix = 40;

Status bad_compact(const std::string& detail) {
  return malformed_section(kVsplTag, "compact: " + detail);
}

int best_golomb_order(const std::vector<uint64_t>& values) {
  int best = 0;
  uint64_t best_bits = UINT64_MAX;
  for (int k = 0; k <= kMaxGolombOrder; ++k) {
    uint64_t total = 0;
    for (uint64_t x : values)
      total += exp_golomb_bits(x, k);
    if (total < best_bits) {
      best_bits = total;
      best = k;
    }
  }
  return best;
}

// The known-neighbour lists that predict the wings (see the file comment).
// The first 8 entries of a list live inline (lists average about 7), the
// rest in a shared overflow vector, so a million-split PM needs no
// allocation per vertex.
class NeighbourLists {
 public:
  static constexpr size_t kInline = 8;
  struct View {
    const uint32_t* head;
    const uint32_t* rest;
    size_t count;
    size_t size() const { return count; }
    bool empty() const { return count == 0; }
    uint32_t operator[](size_t k) const { return k < kInline ? head[k] : rest[k - kInline]; }
  };

  // Lists for the base vertices; split() adds one per new vertex, so memory
  // grows with the records decoded, never with a count read from the file.
  NeighbourLists(size_t base_vertices, const std::vector<Triangle>& triangles)
      : lists_(base_vertices) {
    for (const Triangle& t : triangles) {
      for (int k = 0; k < 3; ++k) {
        add(t[k], t[(k + 1) % 3]);
        add(t[(k + 1) % 3], t[k]);
      }
    }
  }
  // Valid until the next split().
  View of(uint32_t v) const {
    const List& list = lists_[v];
    return {list.head, list.overflow == kNoOverflow ? nullptr : overflow_[list.overflow].data(),
            list.count};
  }
  // \pre vt is the next vertex id (the number of lists so far).
  void split(uint32_t vs, uint32_t vt, uint32_t vl, uint32_t vr) {
    lists_.emplace_back();
    add(vs, vt);
    add(vt, vs);
    for (uint32_t wing : {vl, vr}) {
      add(vt, wing);
      add(wing, vt);
    }
  }

 private:
  static constexpr uint32_t kNoOverflow = UINT32_MAX;
  struct List {
    uint32_t count = 0;
    uint32_t overflow = kNoOverflow;
    uint32_t head[kInline] = {};
  };
  void add(uint32_t a, uint32_t x) {
    if (a == kNoVertex || x == kNoVertex) return;
    List& list = lists_[a];
    if (list.count >= kMaxNeighbours) return;
    const View known = of(a);
    for (size_t k = 0; k < known.size(); ++k) {
      if (known[k] == x) return;
    }
    if (list.count < kInline) {
      list.head[list.count] = x;
    } else {
      if (list.overflow == kNoOverflow) {
        list.overflow = static_cast<uint32_t>(overflow_.size());
        overflow_.emplace_back();
      }
      overflow_[list.overflow].push_back(x);
    }
    ++list.count;
  }
  std::vector<List> lists_;
  std::vector<std::vector<uint32_t>> overflow_;
};

// The fixed fields a compact payload repeats from the raw one.
struct Fixed {
  uint32_t splits = 0;
  uint32_t base = 0;
  bool quantized = false;
  int bits = 0;
  uint8_t flags = 0;
  Vec3f lo{};
  Vec3f hi{};
  size_t bytes = 0;  // 19, or 43 with the box
};

Status read_fixed(const uint8_t* data, size_t size, Fixed* f) {
  ByteReader in(data, size);
  uint8_t encoding = 0;
  uint8_t bits = 0;
  float unused = 0;
  if (!in.read(&f->splits) || !in.read(&f->base) || !in.read(&encoding) || !in.read(&bits) ||
      !in.read(&f->flags) || !in.read(&unused) || !in.read(&unused)) {
    return bad_compact("payload ends inside the fixed fields");
  }
  if (encoding > 1) return bad_compact(string_printf("position encoding %u is unknown", encoding));
  f->quantized = encoding == 1;
  f->bits = bits;
  if (f->quantized && (bits < kMinQuantizationBits || bits > kMaxQuantizationBits))
    return bad_compact(string_printf("quantization bits %u outside 1..30", bits));
  if ((f->flags & ~kVsplKnownFlags) != 0)
    return bad_compact(string_printf("unknown flag bits 0x%02X", f->flags));
  if (f->quantized) {
    for (int a = 0; a < 3; ++a) {
      if (!in.read(&f->lo[a])) return bad_compact("payload ends inside the quantization box");
    }
    for (int a = 0; a < 3; ++a) {
      if (!in.read(&f->hi[a])) return bad_compact("payload ends inside the quantization box");
    }
    int axis = 0;
    if (!is_valid_quantization_box(f->lo, f->hi, &axis))
      return bad_compact(string_printf("quantization box axis %d is not finite and ordered", axis));
  }
  f->bytes = in.position();
  return Status::ok();
}

// vs's quantized position before each split: base vertices quantized into
// the section's box, then each split's integers.
class QuantizedPositions {
 public:
  QuantizedPositions(const Fixed& f, const std::vector<Vec3f>& base)
      : steps_(quantization_steps(f.bits)) {
    q_.resize(base.size() * 3);
    for (size_t v = 0; v < base.size(); ++v) {
      for (int a = 0; a < 3; ++a)
        q_[3 * v + a] = quantize_coordinate(base[v][a], f.lo[a], f.hi[a], steps_);
    }
  }
  uint32_t get(uint32_t v, int a) const { return q_[size_t{v} * 3 + a]; }
  void prefetch(uint32_t v) const { __builtin_prefetch(&q_[size_t{v} * 3]); }
  // vt from the midpoint of its wings when both exist, else from vs.
  int64_t predict_vt(uint32_t vs, uint32_t vl, uint32_t vr, int a) const {
    if (vl == kNoVertex || vr == kNoVertex) return get(vs, a);
    return (int64_t{get(vl, a)} + int64_t{get(vr, a)}) / 2;
  }
  void set(uint32_t v, int a, uint32_t q) { q_[size_t{v} * 3 + a] = q; }
  // The next vertex's position: storage grows with the records decoded, so
  // a hostile split count allocates nothing up front.
  void append(const uint32_t* q) { q_.insert(q_.end(), q, q + 3); }
  // A split's positions: vt's are value[0..2]; vs moves to value[3..5]
  // when the section stores vs positions.
  void apply_split(uint32_t vs, const uint32_t* value, bool with_vs) {
    if (with_vs) {
      for (int a = 0; a < 3; ++a)
        set(vs, a, value[3 + a]);
    }
    append(value);
  }
  uint32_t steps() const { return steps_; }

 private:
  uint32_t steps_;
  std::vector<uint32_t> q_;
};

// The payload decoded, or the caller's decoding of it (`given`).
Result<const VsplSection*> decoded_vspl(const uint8_t* raw, size_t raw_size,
                                        const TriangleMesh& base, const VsplSection* given,
                                        std::optional<VsplSection>* own) {
  if (given != nullptr) return given;
  LODBAKE_ASSIGN_OR_RETURN(VsplSection section, decode_vspl(raw, raw_size, base.positions));
  own->emplace(std::move(section));
  return &**own;
}

Result<Bytes> encode_v1(const uint8_t* raw, size_t raw_size, const TriangleMesh& base,
                        const VsplSection* given) {
  LODBAKE_ASSIGN_OR_RETURN(VsplParts parts, locate_vspl_parts(raw, raw_size));
  std::optional<VsplSection> own;
  LODBAKE_ASSIGN_OR_RETURN(const VsplSection* decoded,
                           decoded_vspl(raw, raw_size, base, given, &own));
  const VsplSection& section = *decoded;
  Fixed f;
  LODBAKE_RETURN_IF_ERROR(read_fixed(raw, raw_size, &f));
  const bool with_vs = (f.flags & kVsplStoresVsPositions) != 0;
  const std::vector<VertexSplit>& splits = section.splits;
  const size_t per_split = with_vs ? 6 : 3;

  // Residuals first, to choose the Golomb orders.
  std::vector<uint64_t> residuals[3];
  if (f.quantized) {
    QuantizedPositions q(f, base.positions);
    BitReader ints(raw + parts.positions_offset, parts.positions_bytes);
    for (size_t i = 0; i < splits.size(); ++i) {
      const uint32_t vs = splits[i].vs;
      uint32_t value[6] = {};
      for (size_t c = 0; c < per_split; ++c)
        ints.read(f.bits, &value[c]);
      for (size_t c = 0; c < per_split; ++c) {
        const int a = static_cast<int>(c % 3);
        const int64_t predicted =
            c < 3 ? q.predict_vt(vs, splits[i].vl, splits[i].vr, a) : int64_t{q.get(vs, a)};
        residuals[a].push_back(zigzag64(int64_t{value[c]} - predicted));
      }
      q.apply_split(vs, value, with_vs);
    }
  }
  std::vector<uint64_t> error_deltas;
  error_deltas.reserve(splits.size());
  uint32_t previous = 0;
  for (const VertexSplit& split : splits) {
    const uint32_t bits = float_bits(split.error);
    error_deltas.push_back(zigzag64(int64_t{bits} - int64_t{previous}));
    previous = bits;
  }

  Bytes out;
  ByteWriter writer(&out);
  writer.write(uint8_t{1});
  writer.write_bytes(raw, f.bytes);
  int order[3] = {0, 0, 0};
  if (f.quantized) {
    for (int a = 0; a < 3; ++a) {
      order[a] = best_golomb_order(residuals[a]);
      writer.write(static_cast<uint8_t>(order[a]));
    }
  }
  const int error_order = best_golomb_order(error_deltas);
  writer.write(static_cast<uint8_t>(error_order));

  for (const Triangle& t : base.triangles) {
    for (uint32_t v : t) {
      if (v >= base.vertex_count())
        return invalid_input("cannot encode compact VSPL: a base triangle index is out of range");
    }
  }
  NeighbourLists lists(f.base, base.triangles);
  BitWriter stream(&out);
  size_t next_residual[3] = {0, 0, 0};
  for (size_t i = 0; i < splits.size(); ++i) {
    const VertexSplit& split = splits[i];
    const uint32_t n = f.base + static_cast<uint32_t>(i);
    stream.write(split.vs, bits_for_count(n));
    const NeighbourLists::View known = lists.of(split.vs);
    for (uint32_t wing : {split.vl, split.vr}) {
      size_t index = known.size();
      for (size_t k = 0; k < known.size() && wing != kNoVertex; ++k) {
        if (known[k] == wing) {
          index = k;
          break;
        }
      }
      if (!known.empty()) stream.write(index < known.size() ? 1 : 0, 1);
      if (index < known.size()) {
        stream.write(static_cast<uint32_t>(index), bits_for_count(known.size()));
      } else {
        stream.write(wing == kNoVertex ? n : wing, bits_for_count(uint64_t{n} + 1));
      }
    }
    if (f.quantized) {
      for (size_t c = 0; c < per_split; ++c) {
        const int a = static_cast<int>(c % 3);
        write_exp_golomb(&stream, residuals[a][next_residual[a]++], order[a]);
      }
    }
    write_exp_golomb(&stream, error_deltas[i], error_order);
    lists.split(split.vs, n, split.vl, split.vr);
  }
  stream.finish();
  if (!f.quantized) writer.write_bytes(raw + parts.positions_offset, parts.positions_bytes);
  writer.write_bytes(raw + parts.tail_offset, raw_size - parts.tail_offset);
  return out;
}

Status check_base_triangles(const TriangleMesh& base) {
  for (const Triangle& t : base.triangles) {
    for (uint32_t v : t) {
      if (v >= base.vertex_count()) return bad_compact("a base triangle index is out of range");
    }
  }
  return Status::ok();
}

// The fixed fields of either layout (after the version byte), checked
// against the base mesh the section refines.
Status read_fixed_for_base(const uint8_t* data, size_t size, const TriangleMesh& base, Fixed* f) {
  LODBAKE_RETURN_IF_ERROR(read_fixed(data + 1, size - 1, f));
  if (f->base != base.vertex_count()) {
    return bad_compact(string_printf("base vertex count %u, but the base mesh has %zu vertices",
                                     f->base, base.vertex_count()));
  }
  if (uint64_t{f->base} + f->splits > UINT32_MAX)
    return bad_compact("base vertices and splits make more than 2^32 - 1 vertices");
  if (f->splits != 0 && f->base < 2)
    return bad_compact("splits over a base of fewer than 2 vertices");
  return Status::ok();
}

// The raw VSPL records a decoder rebuilds, in the raw layout's three
// streams: bit-packed topology (vs, then each wing or n for none), the
// bit-packed quantized positions, and the float32 error bits.
struct RawRecords {
  Bytes topology;
  Bytes positions;
  Bytes errors;
  BitWriter topology_out{&topology};
  BitWriter positions_out{&positions};
  ByteWriter errors_out{&errors};

  // The topology of split n (vt = n), with kNoVertex for a missing wing.
  void write_topology(uint32_t vs, uint32_t vl, uint32_t vr, uint32_t n) {
    const int wing_bits = bits_for_count(uint64_t{n} + 1);
    topology_out.write(vs, bits_for_count(n));
    topology_out.write(vl == kNoVertex ? n : vl, wing_bits);
    topology_out.write(vr == kNoVertex ? n : vr, wing_bits);
  }
  void finish() {
    topology_out.finish();
    positions_out.finish();
  }
};

Result<Bytes> decode_v1(const uint8_t* data, size_t size, const TriangleMesh& base) {
  Fixed f;
  LODBAKE_RETURN_IF_ERROR(read_fixed_for_base(data, size, base, &f));
  const uint64_t r = f.splits;
  size_t pos = 1 + f.bytes;
  int order[3] = {0, 0, 0};
  const int orders = f.quantized ? 4 : 1;
  if (size - pos < static_cast<size_t>(orders)) return bad_compact("payload ends before the codes");
  for (int a = 0; a < orders; ++a) {
    const int k = data[pos + a];
    if (k > kMaxGolombOrder) return bad_compact(string_printf("code order %d above 32", k));
    if (a < 3 && f.quantized) order[a] = k;
  }
  const int error_order = data[pos + orders - 1];
  pos += orders;
  // Each record takes at least 4 bits: vs (n >= 2), two wings, an error code.
  if (r > 2 * uint64_t{size - pos}) {
    return bad_compact(string_printf("%u splits need at least %" PRIu64 " bytes, %zu remain",
                                     f.splits, (4 * r + 7) / 8, size - pos));
  }
  LODBAKE_RETURN_IF_ERROR(check_base_triangles(base));
  const bool with_vs = (f.flags & kVsplStoresVsPositions) != 0;
  const size_t per_split = with_vs ? 6 : 3;

  RawRecords raw;
  std::vector<QuantizedPositions> q;
  if (f.quantized) q.emplace_back(f, base.positions);
  NeighbourLists lists(f.base, base.triangles);
  BitReader in(data + pos, size - pos);
  uint32_t previous = 0;
  for (uint32_t i = 0; i < f.splits; ++i) {
    const uint32_t n = f.base + i;
    uint32_t vs = 0;
    if (!in.read(bits_for_count(n), &vs)) return bad_compact("stream ends inside the splits");
    if (vs >= n) return bad_compact(string_printf("split %u: vs %u out of range (%u)", i, vs, n));
    const NeighbourLists::View known = lists.of(vs);
    uint32_t wing_value[2] = {0, 0};
    for (uint32_t& wing : wing_value) {
      uint32_t hit = 0;
      if (!known.empty() && !in.read(1, &hit)) return bad_compact("stream ends inside the splits");
      if (hit == 1) {
        uint32_t index = 0;
        if (!in.read(bits_for_count(known.size()), &index))
          return bad_compact("stream ends inside the splits");
        if (index >= known.size()) {
          return bad_compact(
              string_printf("split %u: neighbour %u of %zu", i, index, known.size()));
        }
        wing = known[index];
      } else {
        if (!in.read(bits_for_count(uint64_t{n} + 1), &wing))
          return bad_compact("stream ends inside the splits");
        if (wing > n) return bad_compact(string_printf("split %u: wing %u out of range", i, wing));
      }
    }
    const uint32_t vl = wing_value[0] == n ? kNoVertex : wing_value[0];
    const uint32_t vr = wing_value[1] == n ? kNoVertex : wing_value[1];
    raw.write_topology(vs, vl, vr, n);
    if (f.quantized) {
      QuantizedPositions& qp = q.front();
      uint32_t value[6] = {};
      for (size_t c = 0; c < per_split; ++c) {
        const int a = static_cast<int>(c % 3);
        uint64_t z = 0;
        if (!read_exp_golomb(&in, order[a], kMaxGolombPrefix, &z))
          return bad_compact("stream ends inside a position");
        const int64_t predicted = c < 3 ? qp.predict_vt(vs, vl, vr, a) : int64_t{qp.get(vs, a)};
        const int64_t v = predicted + unzigzag64(z);
        if (v < 0 || v > int64_t{qp.steps()}) {
          return bad_compact(string_printf(
              "split %u: position coordinate %" PRId64 " outside 0..%u", i, v, qp.steps()));
        }
        value[c] = static_cast<uint32_t>(v);
        raw.positions_out.write(value[c], f.bits);
      }
      qp.apply_split(vs, value, with_vs);
    }
    uint64_t z = 0;
    if (!read_exp_golomb(&in, error_order, kMaxGolombPrefix, &z))
      return bad_compact("stream ends inside an error");
    const int64_t bits = int64_t{previous} + unzigzag64(z);
    if (bits < 0 || bits > int64_t{UINT32_MAX})
      return bad_compact(string_printf("split %u: error bits out of range", i));
    previous = static_cast<uint32_t>(bits);
    raw.errors_out.write(previous);
    lists.split(vs, n, vl, vr);
  }
  raw.finish();
  if (!in.padding_is_zero()) return bad_compact("nonzero padding bits after the stream");
  pos += in.bytes_consumed();

  const uint64_t full = uint64_t{f.base} + r;
  uint64_t tail = f.quantized ? 0 : 12 * per_split / 3 * r;
  if ((f.flags & kVsplStoresNormals) != 0) tail += 12 * r;
  if ((f.flags & kVsplStoresTexcoords) != 0) tail += 8 * r;
  if ((f.flags & kVsplStoresPermutation) != 0)
    tail += packed_size_bytes(full, bits_for_count(full));
  if (tail != size - pos) {
    return bad_compact(
        string_printf("%zu bytes follow the stream, the flags need %" PRIu64, size - pos, tail));
  }
  Bytes out;
  out.reserve(f.bytes + raw.topology.size() + raw.positions.size() + raw.errors.size() +
              (size - pos));
  out.insert(out.end(), data + 1, data + 1 + f.bytes);
  out.insert(out.end(), raw.topology.begin(), raw.topology.end());
  const uint64_t float_bytes = f.quantized ? 0 : 12 * per_split / 3 * r;
  if (f.quantized) {
    out.insert(out.end(), raw.positions.begin(), raw.positions.end());
  } else {
    out.insert(out.end(), data + pos, data + pos + float_bytes);
  }
  out.insert(out.end(), raw.errors.begin(), raw.errors.end());
  out.insert(out.end(), data + pos + float_bytes, data + size);
  return out;
}

// ---------------------------------------------------------------------------
// Layout versions 2, 3 and 4 (see the file comment).

// From this many splits on, the writer does not try version 1: version 2
// (and 3) is smaller on every real mesh from a few hundred splits up (the
// 2324-split golden mushroom's VSPL: 20 against 25.5 kB), and trying both
// doubles the time.
constexpr uint32_t kVersion1Candidates = 4096;

constexpr uint32_t kWingNone = 62;    // first-wing and lone-wing symbol: no such wing
constexpr uint32_t kWingEscape = 63;  // any wing symbol: the id follows, uniform in [0, n)
constexpr uint32_t kOffsetNone = 0;   // second-wing offset symbol: no vr
constexpr size_t kFanContexts = 64;
constexpr size_t kScaleContexts = 32;
constexpr size_t kErrorContexts = 33;
constexpr size_t kPermutationContexts = 34;

// Context of a fan: closed rings and open fans (boundaries) apart, then the
// neighbour count, which sets the spread of a uniform wing.
size_t fan_context(bool closed, size_t count) {
  return (closed ? 0 : 32) + std::min<size_t>(count, 31);
}

// Context of the second wing: its offset is below the ring size in a closed
// fan, below vl's place in an open one.
size_t offset_context(bool closed, size_t count, size_t vl_index) {
  return closed ? std::min<size_t>(count, 31) : 32 + std::min<size_t>(vl_index, 31);
}

struct Models {
  Models()
      : vs_buckets(6),
        first(kFanContexts, BitTreeModel(6)),
        offset(kFanContexts, BitTreeModel(6)),
        alone(kFanContexts, BitTreeModel(6)),
        position(7 * kScaleContexts),
        error(kErrorContexts),
        permutation(kPermutationContexts) {}
  BitTreeModel vs_buckets;
  std::vector<BitTreeModel> first;
  std::vector<BitTreeModel> offset;
  std::vector<BitTreeModel> alone;
  AdaptiveSignedModel position;
  AdaptiveSignedModel error;
  AdaptiveSignedModel permutation;
};

// The scale context of a split's residuals: the bit length of the largest
// coordinate distance between its wings (or between vs and its one wing),
// since a split's offsets grow with the size of the edges around it.
size_t scale_context(const QuantizedPositions& q, uint32_t vs, uint32_t vl, uint32_t vr) {
  const uint32_t a = vl == kNoVertex ? vs : vl;
  const uint32_t b = vr == kNoVertex ? vs : vr;
  uint32_t largest = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const uint32_t p = q.get(a, axis);
    const uint32_t r = q.get(b, axis);
    largest = std::max(largest, p > r ? p - r : r - p);
  }
  return std::min<size_t>(static_cast<size_t>(AdaptiveIntModel::length_of(largest)),
                          kScaleContexts - 1);
}

// vt's prediction, once the split is applied to `mesh`. The centroid of
// vt's neighbours (vs, the wings and the fan between them): a smooth
// surface passes near the average of a vertex's neighbours. The two axes
// least aligned with the fan's normal are coded first; the third is then
// predicted on the fan's tangent plane through the centroid, since the
// offset from the centroid is mostly tangential. Without a fan (hostile
// records), version 1's rule from the wings. Integer arithmetic only, so
// every platform predicts alike.
struct VtPrediction {
  int64_t centroid[3] = {};
  size_t spread[3] = {};  // per axis: bit length of the neighbours' widest offset
  int order[3] = {0, 1, 2};
  int64_t normal[3] = {};  // fan normal, scaled below 2^16 per axis; 0 without a plane
  // The prediction of coordinate order[c], given the residuals of the
  // coordinates coded before it.
  int64_t predict(int c, const int64_t residual[3]) const {
    const int axis = order[c];
    if (c < 2 || normal[axis] == 0) return centroid[axis];
    const int64_t num =
        -(normal[order[0]] * residual[order[0]] + normal[order[1]] * residual[order[1]]);
    const int64_t den = normal[axis];
    // Rounded to nearest, ties away from zero.
    const int64_t q = (2 * (num < 0 ? -num : num) + den) / (2 * den);
    return centroid[axis] + (num < 0 ? -q : q);
  }
  bool flipped = false;  // the fan's normal pointed down the dominant axis
  // Version 3, with a plane: the bit length of the fan's mean distance
  // from the plane along the dominant axis, which scales the third
  // residual better than the axis's spread; kNoRelief otherwise.
  static constexpr size_t kNoRelief = SIZE_MAX;
  size_t relief = kNoRelief;
  // The context of coordinate order[c]: its axis's spread (or the relief),
  // for the third apart when the normal was flipped.
  size_t context(int c) const {
    const size_t slot = c == 2 && flipped ? 6 : static_cast<size_t>(c);
    return slot * kScaleContexts + (c == 2 && relief != kNoRelief ? relief : spread[order[c]]);
  }
};

int shift_below(uint64_t magnitude, int bits) {
  int shift = 0;
  while ((magnitude >> shift) >= (uint64_t{1} << bits))
    ++shift;
  return shift;
}

// The weights of version 3's prediction, in 64ths: of vs, of the wings'
// midpoint and of the moved vertices' centroid, each against the centroid
// of vt's fan. The writer's choice (a least-squares fit on the bunny and
// the armadillo, which agreed within 0.03), stored in the payload.
struct VtWeights {
  int64_t vs = 26;
  int64_t wings = -6;
  int64_t moved = 12;
};

// n / d rounded to nearest, ties away from zero. \pre d > 0.
int64_t rounded_quotient(int64_t n, int64_t d) {
  const int64_t q = (2 * (n < 0 ? -n : n) + d) / (2 * d);
  return n < 0 ? -q : q;
}

// Version 3's point prediction of vt, per axis: the fan's centroid c
// moved by the weighted offsets of vs, the wings' midpoint and the moved
// vertices' centroid from c, in one exact rational (below 2^58 for fans
// of at most 256 entries, 30-bit coordinates and weights of at most 2).
void weighted_centroid(const QuantizedPositions& q, uint32_t vs, uint32_t vl, uint32_t vr,
                       const std::vector<uint32_t>& ring, const VtWeights& w, int64_t* out) {
  const int64_t k = static_cast<int64_t>(ring.size());
  int64_t moved = 0;
  int64_t sum[3] = {0, 0, 0};
  int64_t moved_sum[3] = {0, 0, 0};
  for (uint32_t v : ring) {
    const bool is_moved = v != vs && v != vl && v != vr;
    moved += is_moved ? 1 : 0;
    for (int a = 0; a < 3; ++a) {
      const int64_t x = q.get(v, a);
      sum[a] += x;
      moved_sum[a] += is_moved ? x : 0;
    }
  }
  const int64_t m = std::max<int64_t>(moved, 1);
  const uint32_t left = vl == kNoVertex ? vs : vl;
  const uint32_t right = vr == kNoVertex ? vs : vr;
  for (int a = 0; a < 3; ++a) {
    // c + w_s (s - c) + w_w ((l + r) / 2 - c) + w_m (M / moved - c), all
    // over 128 k m.
    int64_t num = 128 * m * sum[a] + 2 * m * w.vs * (k * int64_t{q.get(vs, a)} - sum[a]) +
                  m * w.wings * (k * (int64_t{q.get(left, a)} + q.get(right, a)) - 2 * sum[a]);
    if (moved > 0) num += 2 * w.moved * (k * moved_sum[a] - moved * sum[a]);
    out[a] = rounded_quotient(num, 128 * k * m);
  }
}

// `ring` and `closed`: vt's fan after the split (SplitConnectivity::neighbours).
// `weights`: version 3's, or null for version 2's centroid.
VtPrediction predict_vt_v2(const QuantizedPositions& q, uint32_t vs, uint32_t vl, uint32_t vr,
                           const std::vector<uint32_t>* ring, bool closed,
                           const VtWeights* weights = nullptr) {
  VtPrediction p;
  if (ring->empty()) {
    for (int a = 0; a < 3; ++a) {
      p.centroid[a] = q.predict_vt(vs, vl, vr, a);
      p.spread[a] = kScaleContexts - 1;
    }
    return p;
  }
  if (weights != nullptr) {
    weighted_centroid(q, vs, vl, vr, *ring, *weights, p.centroid);
  } else {
    // vs counts twice: the simplifier collapsed vt into vs because it was
    // close, so vt lies nearer to vs than to the rest of its fan (weight 2:
    // 0.05 bit per split less on the bunny, 0.47 on the armadillo; 3 and 4
    // were worse).
    int64_t count = 0;
    for (uint32_t v : *ring)
      count += v == vs ? 2 : 1;
    for (int a = 0; a < 3; ++a) {
      int64_t sum = 0;
      for (uint32_t v : *ring)
        sum += (v == vs ? 2 : 1) * int64_t{q.get(v, a)};
      p.centroid[a] = (sum + count / 2) / count;
    }
  }
  uint64_t widest_all = 0;
  for (int a = 0; a < 3; ++a) {
    uint64_t widest = 0;
    for (uint32_t v : *ring) {
      const int64_t d = int64_t{q.get(v, a)} - p.centroid[a];
      widest = std::max(widest, static_cast<uint64_t>(d < 0 ? -d : d));
    }
    widest_all = std::max(widest_all, widest);
    p.spread[a] = std::min<size_t>(static_cast<size_t>(AdaptiveIntModel::length_of(widest)),
                                   kScaleContexts - 1);
  }
  // Newell's normal of the fan polygon, offsets scaled below 2^20 so that
  // the sums of products stay far inside 64 bits.
  const int shift = shift_below(widest_all, 20);
  int64_t n[3] = {0, 0, 0};
  const size_t edges = closed ? ring->size() : ring->size() - 1;
  for (size_t i = 0; i < edges; ++i) {
    const uint32_t u = (*ring)[i];
    const uint32_t w = (*ring)[(i + 1) % ring->size()];
    int64_t du[3];
    int64_t dw[3];
    for (int a = 0; a < 3; ++a) {
      du[a] = (int64_t{q.get(u, a)} - p.centroid[a]) / (int64_t{1} << shift);
      dw[a] = (int64_t{q.get(w, a)} - p.centroid[a]) / (int64_t{1} << shift);
    }
    n[0] += du[1] * dw[2] - du[2] * dw[1];
    n[1] += du[2] * dw[0] - du[0] * dw[2];
    n[2] += du[0] * dw[1] - du[1] * dw[0];
  }
  uint64_t largest = 0;
  int dominant = 0;
  for (int a = 0; a < 3; ++a) {
    const uint64_t m = static_cast<uint64_t>(n[a] < 0 ? -n[a] : n[a]);
    if (m > largest) {
      largest = m;
      dominant = a;
    }
  }
  if (largest == 0) return p;
  const int normal_shift = shift_below(largest, 16);
  const int64_t sign = n[dominant] < 0 ? -1 : 1;
  p.flipped = sign < 0;
  for (int a = 0; a < 3; ++a)
    p.normal[a] = sign * n[a] / (int64_t{1} << normal_shift);
  if (p.normal[dominant] == 0) {
    for (int64_t& c : p.normal)
      c = 0;
    return p;
  }
  int k = 0;
  for (int a = 0; a < 3; ++a) {
    if (a != dominant) p.order[k++] = a;
  }
  p.order[2] = dominant;
  if (weights != nullptr) {
    // Mean |n . (u - c)| / n_D over the fan: the height of its vertices
    // above the plane through the prediction, along D (below 2^60: n below
    // 2^16 per axis; the prediction is within 3 * 2^31 of the 30-bit
    // centroid for any stored weights, so offsets are below 2^33; at most
    // 256 entries).
    uint64_t height = 0;
    for (uint32_t u : *ring) {
      int64_t dot = 0;
      for (int a = 0; a < 3; ++a)
        dot += p.normal[a] * (int64_t{q.get(u, a)} - p.centroid[a]);
      height += static_cast<uint64_t>(dot < 0 ? -dot : dot);
    }
    const uint64_t mean = height / (static_cast<uint64_t>(p.normal[dominant]) * ring->size());
    p.relief = std::min<size_t>(static_cast<size_t>(AdaptiveIntModel::length_of(mean)),
                                kScaleContexts - 1);
  }
  return p;
}

size_t error_context(int64_t previous_delta) {
  const uint64_t m = previous_delta < 0 ? uint64_t{0} - static_cast<uint64_t>(previous_delta)
                                        : static_cast<uint64_t>(previous_delta);
  return std::min<size_t>(static_cast<size_t>(AdaptiveIntModel::length_of(m)), kErrorContexts - 1);
}

// The permutation: a base vertex's input id is predicted by the previous
// one's + 1 (context 0), all of them before the records; a split vertex's,
// coded with its record, by the median of its fan's input ids (vt's
// neighbours in the full mesh, which input files number close together),
// vs's when the fan is empty, in the context of the fan's widest id
// distance from that median (how scattered the neighbourhood's numbering
// is). Predicting from vs's id alone, with the wings' distance as context,
// cost 0.7 bit more on the bunny; the parallelogram vl + vr - vs in id
// space, 1 bit more.
struct InputPrediction {
  int64_t value = 0;
  size_t context = 0;
};

InputPrediction predict_input(const std::vector<uint32_t>& input, uint32_t vs,
                              const std::vector<uint32_t>& fan, std::vector<int64_t>* ids) {
  InputPrediction p;
  ids->clear();
  for (uint32_t w : fan)
    ids->push_back(input[w]);
  if (ids->empty()) {
    p.value = input[vs];
  } else {
    // Fans hold about six ids, where an insertion sort beats std::sort's
    // set-up; large (hostile) fans keep n log n. Either gives one order.
    if (ids->size() <= 16) {
      int64_t* d = ids->data();
      for (size_t i = 1; i < ids->size(); ++i) {
        const int64_t x = d[i];
        size_t j = i;
        for (; j > 0 && d[j - 1] > x; --j)
          d[j] = d[j - 1];
        d[j] = x;
      }
    } else {
      std::sort(ids->begin(), ids->end());
    }
    p.value = (*ids)[ids->size() / 2];
  }
  uint64_t widest = 0;
  for (int64_t id : *ids)
    widest = std::max(widest, static_cast<uint64_t>(id > p.value ? id - p.value : p.value - id));
  p.context = 1 + std::min<size_t>(static_cast<size_t>(AdaptiveIntModel::length_of(widest)),
                                   kPermutationContexts - 2);
  return p;
}

// vs by the 64th of [0, n) it falls in (adaptive: recently created
// vertices are rarely split soon, so the top 64ths are rare), then
// uniformly within that 64th. Below 128 vertices a 64th may hold one id or
// none, so vs is uniform there: either way each record narrows the coder's
// range by at least one bit, which bounds the record count by the bytes.
constexpr uint32_t kVsBucketsFrom = 128;
uint32_t vs_bucket_start(uint64_t bucket, uint64_t n) {
  return static_cast<uint32_t>((bucket * n + 63) / 64);
}
// The first rank of a class of k ids in its 16th number `bucket`.
uint32_t rank_bucket_start(uint64_t bucket, uint64_t k) {
  return static_cast<uint32_t>((bucket * k + 15) / 16);
}

void encode_vs(RangeEncoder* rc, BitTreeModel* buckets, uint32_t vs, uint32_t n) {
  if (n < kVsBucketsFrom) {
    rc->encode_uniform(vs, n);
    return;
  }
  const uint32_t bucket = static_cast<uint32_t>(uint64_t{vs} * 64 / n);
  buckets->encode(rc, bucket);
  const uint32_t start = vs_bucket_start(bucket, n);
  rc->encode_uniform(vs - start, vs_bucket_start(bucket + 1, n) - start);
}

bool decode_vs(RangeDecoder* rc, BitTreeModel* buckets, uint32_t n, uint32_t* vs) {
  if (n < kVsBucketsFrom) return rc->decode_uniform(n, vs);
  const uint32_t bucket = buckets->decode(rc);
  const uint32_t start = vs_bucket_start(bucket, n);
  uint32_t offset = 0;
  if (!rc->decode_uniform(vs_bucket_start(bucket + 1, n) - start, &offset)) return false;
  *vs = start + offset;
  return true;
}

// Rotates a closed fan of vs to start at its vertex farthest from vs (the
// first of equal ones): the faces that move to vt were vt's, so the far
// vertices lie in the arc between vr and vl.
void start_at_farthest(const QuantizedPositions& q, uint32_t vs, std::vector<uint32_t>* ring) {
  size_t best = 0;
  uint64_t best_d = 0;
  for (size_t k = 0; k < ring->size(); ++k) {
    uint64_t d = 0;
    for (int a = 0; a < 3; ++a) {
      const int64_t x = int64_t{q.get((*ring)[k], a)} - int64_t{q.get(vs, a)};
      d += static_cast<uint64_t>(x * x);
    }
    if (d > best_d) {
      best_d = d;
      best = k;
    }
  }
  std::rotate(ring->begin(), ring->begin() + static_cast<std::ptrdiff_t>(best), ring->end());
}

size_t index_in(const std::vector<uint32_t>& ring, uint32_t v) {
  if (v == kNoVertex) return ring.size();
  return static_cast<size_t>(std::find(ring.begin(), ring.end(), v) - ring.begin());
}

// ---------------------------------------------------------------------------
// Layout version 3 (see the file comment): vs by its fan size, vt from a
// weighted combination of its fan.

// vs's class: the size of its fan when last updated, capped; class 0 (no
// fan) is never coded, so symbol 0 is the escape to version 2's vs code.
constexpr uint32_t kVsClasses = 16;
constexpr uint32_t kVsEscape = 0;
// Ranks in a class of at least 2 * kRankBuckets ids are coded by their
// 16th of the class (adaptive per class), then uniformly inside it.
constexpr uint32_t kRankBuckets = 16;

uint32_t vs_class_of(size_t fan_size) {
  return static_cast<uint32_t>(std::min<size_t>(fan_size, kVsClasses - 1));
}

// A set of ids in [0, size()) with rank and select in O(log n): a bit per
// id and a Fenwick tree of the count in each 64-id word (0.19 bytes an id).
class OrderedIds {
 public:
  size_t size() const { return 64 * words_.size(); }
  uint32_t count() const { return count_; }
  // Room for ids below `ids`, the new ones absent. Memory grows with what
  // the caller adds, never with a count read from a file.
  void grow(size_t ids) {
    while (size() < ids) {
      words_.push_back(0);
      // Fenwick node i (1-based) holds the words (i - lowbit(i), i]; the
      // new word is empty, so it is the sum of the earlier ones in range.
      const size_t i = words_.size();
      tree_.push_back(prefix(i - 1) - prefix(i - (i & (~i + 1))));
    }
  }
  // Every id in [0, ids) present (size() rounds up to a word).
  void fill(size_t ids) {
    words_.assign((ids + 63) / 64, ~uint64_t{0});
    if (ids % 64 != 0) words_.back() = (uint64_t{1} << (ids % 64)) - 1;
    tree_.assign(words_.size(), 0);
    for (size_t i = 1; i <= tree_.size(); ++i) {
      tree_[i - 1] += static_cast<uint32_t>(__builtin_popcountll(words_[i - 1]));
      const size_t up = i + (i & (~i + 1));
      if (up <= tree_.size()) tree_[up - 1] += tree_[i - 1];
    }
    count_ = static_cast<uint32_t>(ids);
  }
  bool contains(uint32_t v) const { return ((words_[v / 64] >> (v % 64)) & 1) != 0; }
  // Adds an absent v or removes a present one. \pre v < size().
  void flip(uint32_t v) {
    const bool add = !contains(v);
    words_[v / 64] ^= uint64_t{1} << (v % 64);
    const uint32_t delta = add ? 1u : UINT32_MAX;
    count_ += delta;
    for (size_t i = v / 64 + 1; i <= tree_.size(); i += i & (~i + 1))
      tree_[i - 1] += delta;
  }
  // The number of ids below v (any v; all of them from size() up).
  uint32_t below(uint64_t v) const {
    if (v >= size()) return count_;
    const uint64_t mask = (uint64_t{1} << (v % 64)) - 1;
    return prefix(static_cast<size_t>(v / 64)) +
           static_cast<uint32_t>(__builtin_popcountll(words_[v / 64] & mask));
  }
  // The id of rank k. \pre k < count().
  uint32_t select(uint32_t k) const {
    size_t word = 0;  // Fenwick descent: the longest prefix of words with at most k ids
    size_t step = 1;
    while (step * 2 <= tree_.size())
      step *= 2;
    for (; step != 0; step /= 2) {
      if (word + step <= tree_.size() && tree_[word + step - 1] <= k) {
        word += step;
        k -= tree_[word - 1];
      }
    }
    uint64_t bits = words_[word];
    for (; k != 0; --k)
      bits &= bits - 1;
    return static_cast<uint32_t>(word * 64 + static_cast<size_t>(__builtin_ctzll(bits)));
  }

 private:
  // The ids in words [0, w).
  uint32_t prefix(size_t w) const {
    uint32_t sum = 0;
    for (; w != 0; w &= w - 1)
      sum += tree_[w - 1];
    return sum;
  }
  std::vector<uint64_t> words_;
  std::vector<uint32_t> tree_;
  uint32_t count_ = 0;
};

// The vertices by class, each class an OrderedIds (3 bytes a vertex for
// 16 classes): a vertex's class is its degree (a count update_classes
// keeps: its fan size on records that fit the mesh), capped at 15.
class VertexClasses {
 public:
  // Vertices 0 .. count - 1, of degree 0.
  explicit VertexClasses(uint32_t count) : classes_(kVsClasses) {
    for (uint32_t v = 0; v < count; ++v)
      add_vertex(0);
  }
  // The next vertex id, of degree d.
  void add_vertex(uint32_t d) {
    const uint32_t v = static_cast<uint32_t>(degree_.size());
    degree_.push_back(d);
    if (v % 64 == 0) {
      for (OrderedIds& set : classes_)
        set.grow(degree_.size());
    }
    classes_[class_of(v)].flip(v);
  }
  uint32_t degree(uint32_t v) const { return degree_[v]; }
  void prefetch(uint32_t v) const { __builtin_prefetch(&degree_[v]); }
  uint32_t class_of(uint32_t v) const { return vs_class_of(degree_[v]); }
  uint32_t count(uint32_t c) const { return classes_[c].count(); }
  void set_degree(uint32_t v, uint32_t d) {
    const uint32_t from = class_of(v);
    degree_[v] = d;
    const uint32_t to = class_of(v);
    if (from == to) return;
    classes_[from].flip(v);
    classes_[to].flip(v);
  }
  // The number of ids of v's class below v.
  uint32_t rank(uint32_t v) const { return classes_[class_of(v)].below(v); }
  // The id of rank k in class c. \pre k < count(c).
  uint32_t select(uint32_t c, uint32_t k) const { return classes_[c].select(k); }

 private:
  std::vector<uint32_t> degree_;
  std::vector<OrderedIds> classes_;
};

struct VsModels {
  VsModels() : classes(4), ranks(kVsClasses, BitTreeModel(4)) {}
  BitTreeModel classes;
  std::vector<BitTreeModel> ranks;
};

// vs in version 3, from n >= 128 vertices: its class's symbol, then its rank
// in the class (uniform, or by 16ths when the class is large); the escape,
// then version 2's code, when its class has fewer than 2 ids (or it has no
// fan). Either way the last step is uniform over at least 2 values, so each
// record still narrows the coder's range by at least one bit.
void encode_vs_v3(RangeEncoder* rc, BitTreeModel* buckets, VsModels* m,
                  const VertexClasses& classes, uint32_t vs, uint32_t n) {
  if (n < kVsBucketsFrom) {
    rc->encode_uniform(vs, n);
    return;
  }
  const uint32_t c = classes.class_of(vs);
  const uint32_t k = c == kVsEscape ? 0 : classes.count(c);
  if (k < 2) {
    m->classes.encode(rc, kVsEscape);
    encode_vs(rc, buckets, vs, n);
    return;
  }
  m->classes.encode(rc, c);
  const uint32_t rank = classes.rank(vs);
  if (k < 2 * kRankBuckets) {
    rc->encode_uniform(rank, k);
    return;
  }
  const uint32_t bucket = static_cast<uint32_t>(uint64_t{rank} * kRankBuckets / k);
  m->ranks[c].encode(rc, bucket);
  const uint32_t start = rank_bucket_start(bucket, k);
  rc->encode_uniform(rank - start, rank_bucket_start(bucket + 1, k) - start);
}

bool decode_vs_v3(RangeDecoder* rc, BitTreeModel* buckets, VsModels* m,
                  const VertexClasses& classes, uint32_t n, uint32_t* vs) {
  if (n < kVsBucketsFrom) return rc->decode_uniform(n, vs);
  const uint32_t c = m->classes.decode(rc);
  if (c == kVsEscape) return decode_vs(rc, buckets, n, vs);
  const uint32_t k = classes.count(c);
  if (k < 2) return false;
  uint32_t rank = 0;
  if (k < 2 * kRankBuckets) {
    if (!rc->decode_uniform(k, &rank)) return false;
  } else {
    const uint32_t bucket = m->ranks[c].decode(rc);
    const uint32_t start = rank_bucket_start(bucket, k);
    uint32_t offset = 0;
    if (!rc->decode_uniform(rank_bucket_start(bucket + 1, k) - start, &offset)) return false;
    rank = start + offset;
  }
  *vs = classes.select(c, rank);
  return true;
}

uint64_t verbatim_bytes(const Fixed& f) {
  const uint64_t r = f.splits;
  const uint64_t per_split = (f.flags & kVsplStoresVsPositions) != 0 ? 24 : 12;
  uint64_t bytes = f.quantized ? 0 : per_split * r;
  if ((f.flags & kVsplStoresNormals) != 0) bytes += 12 * r;
  if ((f.flags & kVsplStoresTexcoords) != 0) bytes += 8 * r;
  return bytes;
}

// Every base vertex's degree: its fan size.
void init_classes(const SplitConnectivity& mesh, uint32_t base, VertexClasses* classes,
                  std::vector<uint32_t>* fan) {
  for (uint32_t v = 0; v < base; ++v) {
    mesh.neighbours(v, fan);
    classes->set_degree(v, static_cast<uint32_t>(fan->size()));
  }
}

// After a split creating vt, the degrees as the split changes fan sizes,
// without walking more fans: vt's is its fan's size; vs trades the moved
// vertices (vt's fan but for vs and the wings) for vt; each wing gains vt;
// a moved vertex trades vs for vt. Exact on records that fit the mesh;
// on others, merely the same in encoder and decoder.
void update_classes(uint32_t vs, uint32_t vl, uint32_t vr, const std::vector<uint32_t>& vt_fan,
                    VertexClasses* classes) {
  uint32_t moved = 0;
  for (uint32_t v : vt_fan)
    moved += v != vs && v != vl && v != vr ? 1 : 0;
  classes->add_vertex(static_cast<uint32_t>(vt_fan.size()));  // vt
  const uint32_t d = classes->degree(vs) + 1;
  classes->set_degree(vs, d > moved ? d - moved : 0);
  for (uint32_t v : {vl, vr}) {
    if (v != kNoVertex) classes->set_degree(v, classes->degree(v) + 1);
  }
}

// Starts loading what a record reads of vs's neighbours once `ring` is
// known: their positions, input ids, degrees and face lists (the wings get
// faces). The vertices are scattered over arrays larger than the caches;
// starting their loads together saves waiting for each stage in turn (2%
// on the dragon). Hints only: nothing coded depends on them.
void prefetch_ring(const SplitConnectivity& mesh, const QuantizedPositions* q,
                   const std::vector<uint32_t>* input, const VertexClasses* classes,
                   const std::vector<uint32_t>& ring) {
  for (uint32_t v : ring) {
    if (q != nullptr) q->prefetch(v);
    if (input != nullptr && v < input->size()) __builtin_prefetch(input->data() + v);
    if (classes != nullptr) classes->prefetch(v);
    mesh.prefetch(v);
  }
}

// Version 4's error shift: the number of low bits that every error's bit
// pattern has zero (errors rounded to fewer significant bits), 0 when no
// error is nonzero. The canonical shift: the decoder refuses a smaller one.
int error_shift(const uint8_t* raw, const VsplParts& parts) {
  uint32_t all = 0;
  for (uint32_t i = 0; i < parts.summary.split_count; ++i) {
    uint32_t bits = 0;
    std::memcpy(&bits, raw + parts.errors_offset + size_t{4} * i, 4);
    all |= bits;
  }
  return all == 0 ? 0 : __builtin_ctz(all);
}

// Versions 2, 3 and 4 (see the file comment).
Result<Bytes> encode_v2(const uint8_t* raw, size_t raw_size, const TriangleMesh& base,
                        uint8_t version, VsplCompactStats* stats, const VsplSection* given) {
  LODBAKE_ASSIGN_OR_RETURN(VsplParts parts, locate_vspl_parts(raw, raw_size));
  std::optional<VsplSection> own;
  LODBAKE_ASSIGN_OR_RETURN(const VsplSection* decoded,
                           decoded_vspl(raw, raw_size, base, given, &own));
  const VsplSection& section = *decoded;
  Fixed f;
  LODBAKE_RETURN_IF_ERROR(read_fixed(raw, raw_size, &f));
  LODBAKE_RETURN_IF_ERROR(check_base_triangles(base));
  const bool with_vs = (f.flags & kVsplStoresVsPositions) != 0;
  const size_t per_split = with_vs ? 6 : 3;
  const std::vector<VertexSplit>& splits = section.splits;
  VsplCompactStats local;
  VsplCompactStats& cost = stats != nullptr ? *stats : local;
  cost = VsplCompactStats{};

  Bytes out;
  ByteWriter writer(&out);
  writer.write(version);
  writer.write_bytes(raw, f.bytes);
  // Version 4 is version 3 with the errors' common zero low bits left out.
  const bool v3 = version >= 3;
  const int shift = version == 4 ? error_shift(raw, parts) : 0;
  if (version == 4) writer.write(static_cast<uint8_t>(shift));
  const VtWeights weights;
  if (v3 && f.quantized) {
    for (int64_t w : {weights.vs, weights.wings, weights.moved})
      writer.write(static_cast<uint8_t>(static_cast<int8_t>(w)));
  }
  const size_t verbatim_start = out.size();
  if (!f.quantized) writer.write_bytes(raw + parts.positions_offset, parts.positions_bytes);
  const uint64_t attributes = verbatim_bytes(f) - (f.quantized ? 0 : parts.positions_bytes);
  writer.write_bytes(raw + parts.tail_offset, static_cast<size_t>(attributes));
  cost.verbatim_bytes = out.size() - verbatim_start;

  RangeEncoder rc(&out);
  Models m;
  SplitConnectivity mesh(f.base, base.triangles);
  mesh.reserve(size_t{f.base} + splits.size(), base.triangles.size() + 2 * splits.size());
  std::vector<QuantizedPositions> q;
  if (f.quantized) q.emplace_back(f, base.positions);
  BitReader ints(raw + parts.positions_offset, parts.positions_bytes);
  std::vector<uint32_t> ring;
  uint32_t previous_error = 0;
  int64_t previous_delta = 0;
  double mark = 0;
  auto spend = [&](double* part) {
    *part += rc.cost_bits() - mark;
    mark = rc.cost_bits();
  };
  const bool with_permutation = (f.flags & kVsplStoresPermutation) != 0;
  const std::vector<uint32_t>& input = section.input_vertex;
  // Version 3: the input ids not yet coded; decode_vspl checked that the
  // permutation is one.
  OrderedIds unused;
  if (v3 && with_permutation) unused.fill(input.size());
  auto encode_input = [&](size_t context, int64_t predicted, uint32_t id) {
    if (v3) {
      m.permutation.encode(
          &rc, context,
          int64_t{unused.below(id)} - int64_t{unused.below(static_cast<uint64_t>(predicted))});
      unused.flip(id);
    } else {
      m.permutation.encode(&rc, context, int64_t{id} - predicted);
    }
  };
  if (with_permutation) {
    for (uint32_t v = 0; v < f.base; ++v)
      encode_input(0, v == 0 ? 0 : int64_t{input[v - 1]} + 1, input[v]);
    spend(&cost.permutation_bits);
  }
  std::vector<uint32_t> vt_ring;
  std::vector<int64_t> ids;
  VsModels vs_models;
  VertexClasses classes(v3 ? f.base : 0);
  std::vector<uint32_t> fan;
  if (v3) init_classes(mesh, f.base, &classes, &fan);
  for (size_t i = 0; i < splits.size(); ++i) {
    const VertexSplit& s = splits[i];
    const uint32_t n = f.base + static_cast<uint32_t>(i);
    // The writer knows the next records' vs: their fans' loads start two
    // and one records ahead (the decoder learns vs only when it reads it).
    if (i + 2 < splits.size() && splits[i + 2].vs < n) mesh.prefetch(splits[i + 2].vs);
    if (i + 1 < splits.size()) {
      mesh.prefetch_faces(splits[i + 1].vs);
      if (v3 && splits[i + 1].vs < n) classes.prefetch(splits[i + 1].vs);
    }
    if (v3) {
      encode_vs_v3(&rc, &m.vs_buckets, &vs_models, classes, s.vs, n);
    } else {
      encode_vs(&rc, &m.vs_buckets, s.vs, n);
    }
    spend(&cost.vs_bits);

    const bool closed = mesh.neighbours(s.vs, &ring);
    prefetch_ring(mesh, f.quantized ? &q.front() : nullptr, with_permutation ? &input : nullptr,
                  v3 ? &classes : nullptr, ring);
    if (closed && f.quantized) start_at_farthest(q.front(), s.vs, &ring);
    const size_t count = ring.size();
    const size_t il = index_in(ring, s.vl);
    const uint32_t first = s.vl == kNoVertex                         ? kWingNone
                           : il < std::min<size_t>(count, kWingNone) ? static_cast<uint32_t>(il)
                                                                     : kWingEscape;
    m.first[fan_context(closed, count)].encode(&rc, first);
    if (first == kWingEscape) rc.encode_uniform(s.vl, n);
    const size_t ir = index_in(ring, s.vr);
    if (first < kWingNone) {
      // vr by its offset back from vl along the fan: the faces that move.
      uint32_t symbol = kWingEscape;
      if (s.vr == kNoVertex) {
        symbol = kOffsetNone;
      } else if (ir < count) {
        const size_t k = closed ? (il + count - ir) % count : (ir < il ? il - ir : 0);
        if (k >= 1 && k < kWingNone) symbol = static_cast<uint32_t>(k);
      }
      m.offset[offset_context(closed, count, il)].encode(&rc, symbol);
      if (symbol == kWingEscape) rc.encode_uniform(s.vr, n);
    } else {
      const uint32_t symbol = s.vr == kNoVertex                         ? kWingNone
                              : ir < std::min<size_t>(count, kWingNone) ? static_cast<uint32_t>(ir)
                                                                        : kWingEscape;
      m.alone[fan_context(closed, count)].encode(&rc, symbol);
      if (symbol == kWingEscape) rc.encode_uniform(s.vr, n);
    }
    spend(&cost.wing_bits);
    mesh.split(s.vs, s.vl, s.vr);
    const bool vt_closed = mesh.neighbours(n, &vt_ring);
    if (v3) update_classes(s.vs, s.vl, s.vr, vt_ring, &classes);

    if (f.quantized) {
      QuantizedPositions& qp = q.front();
      const size_t scale = scale_context(qp, s.vs, s.vl, s.vr);
      const VtPrediction p =
          predict_vt_v2(qp, s.vs, s.vl, s.vr, &vt_ring, vt_closed, v3 ? &weights : nullptr);
      uint32_t value[6] = {};
      for (size_t c = 0; c < per_split; ++c)
        ints.read(f.bits, &value[c]);
      int64_t residual[3] = {};
      for (int c = 0; c < 3; ++c) {
        const int a = p.order[c];
        residual[a] = int64_t{value[a]} - p.predict(c, residual);
        m.position.encode(&rc, p.context(c), residual[a]);
      }
      for (size_t c = 3; c < per_split; ++c) {
        const int a = static_cast<int>(c % 3);
        m.position.encode(&rc, c * kScaleContexts + scale,
                          int64_t{value[c]} - int64_t{qp.get(s.vs, a)});
      }
      qp.apply_split(s.vs, value, with_vs);
      spend(&cost.position_bits);
    }

    const uint32_t bits = float_bits(s.error) >> shift;
    const int64_t delta = int64_t{bits} - int64_t{previous_error};
    m.error.encode(&rc, error_context(previous_delta), delta);
    previous_error = bits;
    previous_delta = delta;
    spend(&cost.error_bits);

    if (with_permutation) {
      const InputPrediction p = predict_input(input, s.vs, vt_ring, &ids);
      encode_input(p.context, p.value, input[n]);
      spend(&cost.permutation_bits);
    }
  }
  rc.finish();
  return out;
}

Result<Bytes> decode_v2(const uint8_t* data, size_t size, const TriangleMesh& base) {
  Fixed f;
  LODBAKE_RETURN_IF_ERROR(read_fixed_for_base(data, size, base, &f));
  const uint64_t r = f.splits;
  const bool v3 = data[0] >= 3;
  size_t pos = 1 + f.bytes;
  int shift = 0;
  if (data[0] == 4) {
    if (size - pos < 1) return bad_compact("payload ends before the error shift");
    shift = data[pos++];
    if (shift > 31) return bad_compact(string_printf("error shift %d outside 0..31", shift));
  }
  const int64_t max_shifted_error = int64_t{UINT32_MAX >> shift};
  uint32_t all_errors = 0;  // every shifted error ORed, for the canonical shift
  VtWeights weights;
  if (v3 && f.quantized) {
    if (size - pos < 3) return bad_compact("payload ends inside the prediction weights");
    weights.vs = static_cast<int8_t>(data[pos]);
    weights.wings = static_cast<int8_t>(data[pos + 1]);
    weights.moved = static_cast<int8_t>(data[pos + 2]);
    pos += 3;
  }
  const uint64_t verbatim = verbatim_bytes(f);
  if (verbatim > size - pos) {
    return bad_compact(string_printf("%u splits need %" PRIu64 " verbatim bytes, %zu remain",
                                     f.splits, verbatim, size - pos));
  }
  const uint8_t* stream = data + pos + verbatim;
  const size_t stream_size = size - pos - static_cast<size_t>(verbatim);
  // Each record codes vs uniformly among n >= 2 vertices, which narrows the
  // coder's range by at least one bit, and the range gains 8 bits per byte
  // read: a stream of S bytes holds fewer than 8 S records.
  if (r > 8 * uint64_t{stream_size}) {
    return bad_compact(
        string_printf("%u splits cannot fit in a stream of %zu bytes", f.splits, stream_size));
  }
  LODBAKE_RETURN_IF_ERROR(check_base_triangles(base));
  const bool with_vs = (f.flags & kVsplStoresVsPositions) != 0;
  const size_t per_split = with_vs ? 6 : 3;

  RangeDecoder rc(stream, stream_size);
  if (!rc.valid_start()) return bad_compact("the range-coded stream has no valid start");
  RawRecords raw;
  Models m;
  SplitConnectivity mesh(f.base, base.triangles);
  std::vector<QuantizedPositions> q;
  if (f.quantized) q.emplace_back(f, base.positions);
  std::vector<uint32_t> ring;
  const bool with_permutation = (f.flags & kVsplStoresPermutation) != 0;
  const uint64_t full = uint64_t{f.base} + r;
  // The input ids decoded so far: the base's first, then one per record.
  std::vector<uint32_t> input;
  // Version 3: the input ids not yet decoded (r is bounded by the stream
  // size above, so the set's 0.19 bytes an id are too).
  OrderedIds unused;
  if (v3 && with_permutation) unused.fill(static_cast<size_t>(full));
  auto decode_input = [&](size_t context, int64_t predicted, uint64_t v) -> Status {
    int64_t delta = 0;
    if (!m.permutation.decode(&rc, context, &delta))
      return bad_compact("a permutation code is out of range");
    if (v3) {
      // The rank of the id among the unused ones, against the prediction's.
      const int64_t rank = int64_t{unused.below(static_cast<uint64_t>(predicted))} + delta;
      if (rank < 0 || rank >= int64_t{unused.count()}) {
        return bad_compact(string_printf("input vertex rank %" PRId64 " of vertex %" PRIu64
                                         " outside the %u unused ids",
                                         rank, v, unused.count()));
      }
      const uint32_t id = unused.select(static_cast<uint32_t>(rank));
      unused.flip(id);
      input.push_back(id);
      return Status::ok();
    }
    const int64_t value = predicted + delta;
    if (value < 0 || static_cast<uint64_t>(value) >= full) {
      return bad_compact(string_printf("input vertex %" PRId64 " of vertex %" PRIu64
                                       " outside 0..%" PRIu64,
                                       value, v, full - 1));
    }
    input.push_back(static_cast<uint32_t>(value));
    return Status::ok();
  };
  if (with_permutation) {
    for (uint32_t v = 0; v < f.base; ++v) {
      LODBAKE_RETURN_IF_ERROR(decode_input(0, v == 0 ? 0 : int64_t{input[v - 1]} + 1, v));
      if (rc.overrun()) return bad_compact("the stream ends inside the permutation");
    }
  }
  std::vector<uint32_t> vt_ring;
  std::vector<int64_t> ids;
  uint32_t previous_error = 0;
  int64_t previous_delta = 0;
  VsModels vs_models;
  VertexClasses classes(v3 ? f.base : 0);
  std::vector<uint32_t> fan;
  if (v3) init_classes(mesh, f.base, &classes, &fan);
  for (uint32_t i = 0; i < f.splits; ++i) {
    const uint32_t n = f.base + i;
    // The message prefix is built only on failure: a string per record
    // would be the decoder's largest cost.
    const auto bad = [i](const std::string& detail) {
      return bad_compact(string_printf("split %u: ", i) + detail);
    };
    uint32_t vs = 0;
    if (v3 ? !decode_vs_v3(&rc, &m.vs_buckets, &vs_models, classes, n, &vs)
           : !decode_vs(&rc, &m.vs_buckets, n, &vs))
      return bad("vs out of range");

    if (v3) classes.prefetch(vs);
    const bool closed = mesh.neighbours(vs, &ring);
    prefetch_ring(mesh, f.quantized ? &q.front() : nullptr, with_permutation ? &input : nullptr,
                  v3 ? &classes : nullptr, ring);
    if (closed && f.quantized) start_at_farthest(q.front(), vs, &ring);
    const size_t count = ring.size();
    uint32_t vl = kNoVertex;
    uint32_t vr = kNoVertex;
    const uint32_t first = m.first[fan_context(closed, count)].decode(&rc);
    if (first == kWingEscape) {
      if (!rc.decode_uniform(n, &vl)) return bad("vl out of range");
    } else if (first < kWingNone) {
      if (first >= count) return bad("vl's place is outside vs's fan");
      vl = ring[first];
    }
    if (first < kWingNone) {
      const uint32_t k = m.offset[offset_context(closed, count, first)].decode(&rc);
      if (k == kWingEscape) {
        if (!rc.decode_uniform(n, &vr)) return bad("vr out of range");
      } else if (k != kOffsetNone) {
        if (k == kWingNone || k >= count || (!closed && k > first))
          return bad("vr's offset from vl is outside vs's fan");
        vr = ring[closed ? (first + count - k) % count : first - k];
      }
    } else {
      const uint32_t symbol = m.alone[fan_context(closed, count)].decode(&rc);
      if (symbol == kWingEscape) {
        if (!rc.decode_uniform(n, &vr)) return bad("vr out of range");
      } else if (symbol < kWingNone) {
        if (symbol >= count) return bad("vr's place is outside vs's fan");
        vr = ring[symbol];
      }
    }
    if (vl == kNoVertex && vr == kNoVertex) return bad("both wings are missing");
    if (vl == vs || vr == vs || (vl == vr && vl != kNoVertex)) return bad("a repeated vertex");
    raw.write_topology(vs, vl, vr, n);
    mesh.split(vs, vl, vr);
    const bool vt_closed = mesh.neighbours(n, &vt_ring);
    if (v3) update_classes(vs, vl, vr, vt_ring, &classes);

    if (f.quantized) {
      QuantizedPositions& qp = q.front();
      const size_t scale = scale_context(qp, vs, vl, vr);
      const VtPrediction p =
          predict_vt_v2(qp, vs, vl, vr, &vt_ring, vt_closed, v3 ? &weights : nullptr);
      uint32_t value[6] = {};
      int64_t residual[3] = {};
      for (size_t c = 0; c < per_split; ++c) {
        const int a = c < 3 ? p.order[c] : static_cast<int>(c % 3);
        const size_t context = c < 3 ? p.context(static_cast<int>(c)) : c * kScaleContexts + scale;
        int64_t decoded = 0;
        if (!m.position.decode(&rc, context, &decoded))
          return bad("a position residual code is out of range");
        const int64_t predicted =
            c < 3 ? p.predict(static_cast<int>(c), residual) : int64_t{qp.get(vs, a)};
        if (c < 3) residual[a] = decoded;
        const int64_t v = predicted + decoded;
        if (v < 0 || v > int64_t{qp.steps()}) {
          return bad(string_printf("position coordinate %" PRId64 " outside 0..%u", v, qp.steps()));
        }
        value[c < 3 ? a : c] = static_cast<uint32_t>(v);
      }
      for (size_t c = 0; c < per_split; ++c)
        raw.positions_out.write(value[c], f.bits);
      qp.apply_split(vs, value, with_vs);
    }

    int64_t delta = 0;
    if (!m.error.decode(&rc, error_context(previous_delta), &delta))
      return bad("an error code is out of range");
    const int64_t bits = int64_t{previous_error} + delta;
    if (bits < 0 || bits > max_shifted_error) return bad("error bits out of range");
    previous_error = static_cast<uint32_t>(bits);
    previous_delta = delta;
    all_errors |= previous_error;
    raw.errors_out.write(previous_error << shift);
    if (with_permutation) {
      const InputPrediction p = predict_input(input, vs, vt_ring, &ids);
      LODBAKE_RETURN_IF_ERROR(decode_input(p.context, p.value, n));
    }
    if (rc.overrun()) return bad("the stream ends inside the record");
  }
  raw.finish();

  Bytes permutation;
  if (with_permutation) {
    BitWriter permutation_out(&permutation);
    const int width = bits_for_count(full);
    for (uint32_t id : input)
      permutation_out.write(id, width);
    permutation_out.finish();
  }
  if (!rc.at_end()) {
    return bad_compact(rc.overrun() ? "the range-coded stream ends early"
                                    : "bytes follow the range-coded stream");
  }
  // One payload per raw payload: the shift must be the largest that fits.
  if (data[0] == 4 && (all_errors == 0 ? shift != 0 : (all_errors & 1) == 0)) {
    return bad_compact(string_printf("error shift %d is not the errors' largest", shift));
  }

  const uint64_t float_bytes = f.quantized ? 0 : 4 * per_split * r;
  const uint8_t* verbatim_data = data + pos;
  Bytes out;
  out.reserve(f.bytes + raw.topology.size() + raw.positions.size() + raw.errors.size() + verbatim +
              permutation.size());
  out.insert(out.end(), data + 1, data + 1 + f.bytes);
  out.insert(out.end(), raw.topology.begin(), raw.topology.end());
  if (f.quantized) {
    out.insert(out.end(), raw.positions.begin(), raw.positions.end());
  } else {
    out.insert(out.end(), verbatim_data, verbatim_data + float_bytes);
  }
  out.insert(out.end(), raw.errors.begin(), raw.errors.end());
  out.insert(out.end(), verbatim_data + float_bytes, verbatim_data + verbatim);
  out.insert(out.end(), permutation.begin(), permutation.end());
  return out;
}

}  // namespace

Result<Bytes> encode_vspl_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base,
                                  const VsplCompactOptions& options) {
  try {
    if (options.version == 1) return encode_v1(raw, raw_size, base, options.decoded);
    if (options.version >= 2 && options.version <= 4)
      return encode_v2(raw, raw_size, base, options.version, options.stats, options.decoded);
    if (options.version == 0) {
      // Version 4 only where it saves bits: errors with common zero low bits.
      LODBAKE_ASSIGN_OR_RETURN(VsplParts parts, locate_vspl_parts(raw, raw_size));
      const uint8_t newest = error_shift(raw, parts) > 0 ? 4 : 3;
      LODBAKE_ASSIGN_OR_RETURN(
          Bytes v3, encode_v2(raw, raw_size, base, newest, options.stats, options.decoded));
      uint32_t splits = 0;
      std::memcpy(&splits, raw, 4);  // encode_v2 checked the payload
      if (splits >= kVersion1Candidates) return v3;
      LODBAKE_ASSIGN_OR_RETURN(Bytes v1, encode_v1(raw, raw_size, base, options.decoded));
      return v1.size() < v3.size() ? v1 : v3;
    }
    return invalid_input(
        string_printf("cannot encode compact VSPL: layout version %u is unknown", options.version));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact VSPL");
  }
}

Result<Bytes> decode_vspl_compact(const uint8_t* data, size_t size, const TriangleMesh& base) {
  try {
    if (size < 1) return bad_compact("payload is empty");
    if (data[0] == 1) return decode_v1(data, size, base);
    if (data[0] >= 2 && data[0] <= 4) return decode_v2(data, size, base);
    return bad_compact(
        string_printf("layout version %u is unknown (this reader knows 1 to 4)", data[0]));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact VSPL");
  }
}

}  // namespace lodbake
