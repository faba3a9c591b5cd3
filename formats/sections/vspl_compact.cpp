// Compact VSPL (codec 1): a lossless recoding of a raw VSPL payload, layout
// in docs/format.md "Compact VSPL". Progressive-mesh coding after Hoppe
// 1996 ("Progressive meshes", section 5: vs as an index, wings relative to
// vs, positions predicted from vs), without replaying the connectivity.
//
// Choices, measured on the Stanford bunny's full PM (34795 splits):
// - vs stays a bits(n) index: QEM order makes it uniform over the mesh
//   (entropy of n - vs: 13.96 bits at log2 n = 13.66), so coding it
//   relative to anything saves nothing.
// - Wings relative to vs as raw ids (vl - vs) have an entropy of 14 bits:
//   ids carry no locality. Instead each vertex keeps a list of vertices it
//   is known to neighbour (the base mesh's edges, then every split's new
//   edges vs-vt, vt-vl, vt-vr), in insertion order, capped at 64 entries
//   (255 gave the same sizes on the bunny and the dragon, with longer
//   scans). A wing found in vs's list costs 1 + bits(list size) bits,
//   otherwise 1 + bits(n + 1). On the bunny 63% are found in lists of 7 on
//   average: about 8.3 bits per wing instead of 14. Replaying the connectivity would
//   find every wing (Hoppe's ~5 bits) but needs the replay in the reader;
//   the lists need no mesh and cannot fail on hostile records.
// - Quantized positions, in the section's own box and bits (a base vertex's
//   float position is quantized into that box first, clamped): vt minus the
//   midpoint of its wings vl and vr (vs's position when a wing is missing),
//   a stored vs minus vs's position before the split; zigzag, then
//   Exp-Golomb of the order k that is smallest for each axis (k stored).
//   Mean log2(|residual| + 1) per coordinate on the bunny at 14 bits: 5.57
//   predicting from vs, 5.28 by the parallelogram vl + vr - vs, 5.20 from
//   the centroid of vs, vl, vr, 5.03 from the wings' midpoint. QEM collapses
//   short edges in any direction, so vt is not where a regular mesh's
//   parallelogram puts it.
//   Float32 positions are copied: they cannot be predicted losslessly
//   without a float residual coder, and packing quantizes them on request.
// - Errors (float32, exact): the difference of each error's bit pattern
//   from the previous one, zigzag, Exp-Golomb with the best k. Collapse
//   costs are not monotone, but neighbours share exponent bits.
// - Normals, texture coordinates and the permutation are copied unchanged.
// - One interleaved bit stream, record after record, so the decoder needs
//   no per-part sizes: it checks the tail's exact size after the stream.
#include "formats/sections/vspl_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/vspl.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/quantization.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

constexpr size_t kMaxNeighbours = 64;
constexpr int kMaxGolombOrder = 32;
constexpr int kMaxGolombPrefix = 40;

Status bad_compact(const std::string& detail) {
  return malformed_section(kVsplTag, "compact: " + detail);
}

uint64_t zigzag(int64_t d) {
  return (static_cast<uint64_t>(d) << 1) ^ static_cast<uint64_t>(d >> 63);
}
int64_t unzigzag(uint64_t z) {
  return static_cast<int64_t>(z >> 1) ^ -static_cast<int64_t>(z & 1);
}

int bit_length(uint64_t x) {
  int n = 0;
  while (x != 0) {
    ++n;
    x >>= 1;
  }
  return n;
}

// Exp-Golomb of order k: y = x + 2^k takes L = bit_length(y) bits; the code
// is L - k - 1 zero bits, a one bit, then the low L - 1 bits of y.
uint64_t golomb_bits(uint64_t x, int k) {
  const int length = bit_length(x + (uint64_t{1} << k));
  return static_cast<uint64_t>(2 * length - k - 1);
}

int best_golomb_order(const std::vector<uint64_t>& values) {
  int best = 0;
  uint64_t best_bits = UINT64_MAX;
  for (int k = 0; k <= kMaxGolombOrder; ++k) {
    uint64_t total = 0;
    for (uint64_t x : values)
      total += golomb_bits(x, k);
    if (total < best_bits) {
      best_bits = total;
      best = k;
    }
  }
  return best;
}

void write_wide(BitWriter* out, uint64_t value, int bits) {
  if (bits > 32) {
    out->write(static_cast<uint32_t>(value & 0xFFFFFFFFu), 32);
    out->write(static_cast<uint32_t>(value >> 32), bits - 32);
  } else {
    out->write(static_cast<uint32_t>(value), bits);
  }
}

bool read_wide(BitReader* in, int bits, uint64_t* value) {
  uint32_t low = 0;
  uint32_t high = 0;
  if (bits > 32) {
    if (!in->read(32, &low) || !in->read(bits - 32, &high)) return false;
  } else if (!in->read(bits, &low)) {
    return false;
  }
  *value = (uint64_t{high} << 32) | low;
  return true;
}

void write_golomb(BitWriter* out, uint64_t x, int k) {
  const uint64_t y = x + (uint64_t{1} << k);
  const int length = bit_length(y);
  for (int i = 0; i < length - k - 1; ++i)
    out->write(0, 1);
  out->write(1, 1);
  write_wide(out, y & ((uint64_t{1} << (length - 1)) - 1), length - 1);
}

bool read_golomb(BitReader* in, int k, uint64_t* x) {
  int zeros = 0;
  for (;;) {
    uint32_t bit = 0;
    if (!in->read(1, &bit)) return false;
    if (bit == 1) break;
    if (++zeros > kMaxGolombPrefix) return false;
  }
  const int low_bits = zeros + k;
  uint64_t low = 0;
  if (!read_wide(in, low_bits, &low)) return false;
  *x = ((uint64_t{1} << low_bits) | low) - (uint64_t{1} << k);
  return true;
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
  // vt from the midpoint of its wings when both exist, else from vs.
  int64_t predict_vt(uint32_t vs, uint32_t vl, uint32_t vr, int a) const {
    if (vl == kNoVertex || vr == kNoVertex) return get(vs, a);
    return (int64_t{get(vl, a)} + int64_t{get(vr, a)}) / 2;
  }
  void set(uint32_t v, int a, uint32_t q) { q_[size_t{v} * 3 + a] = q; }
  // The next vertex's position: storage grows with the records decoded, so
  // a hostile split count allocates nothing up front.
  void append(const uint32_t* q) { q_.insert(q_.end(), q, q + 3); }
  uint32_t steps() const { return steps_; }

 private:
  uint32_t steps_;
  std::vector<uint32_t> q_;
};

Result<Bytes> encode_unchecked(const uint8_t* raw, size_t raw_size, const TriangleMesh& base) {
  LODBAKE_ASSIGN_OR_RETURN(VsplParts parts, locate_vspl_parts(raw, raw_size));
  LODBAKE_ASSIGN_OR_RETURN(VsplSection section, decode_vspl(raw, raw_size, base.positions));
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
        residuals[a].push_back(zigzag(int64_t{value[c]} - predicted));
      }
      if (with_vs) {
        for (int a = 0; a < 3; ++a)
          q.set(vs, a, value[3 + a]);
      }
      q.append(value);
    }
  }
  std::vector<uint64_t> error_deltas;
  error_deltas.reserve(splits.size());
  uint32_t previous = 0;
  for (const VertexSplit& split : splits) {
    const uint32_t bits = float_bits(split.error);
    error_deltas.push_back(zigzag(int64_t{bits} - int64_t{previous}));
    previous = bits;
  }

  Bytes out;
  ByteWriter writer(&out);
  writer.write(kVsplCompactVersion);
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
        write_golomb(&stream, residuals[a][next_residual[a]++], order[a]);
      }
    }
    write_golomb(&stream, error_deltas[i], error_order);
    lists.split(split.vs, n, split.vl, split.vr);
  }
  stream.finish();
  if (!f.quantized) writer.write_bytes(raw + parts.positions_offset, parts.positions_bytes);
  writer.write_bytes(raw + parts.tail_offset, raw_size - parts.tail_offset);
  return out;
}

Result<Bytes> decode_unchecked(const uint8_t* data, size_t size, const TriangleMesh& base) {
  if (size < 1) return bad_compact("payload is empty");
  if (data[0] != kVsplCompactVersion) {
    return bad_compact(string_printf("layout version %u is unknown (this reader knows %u)", data[0],
                                     kVsplCompactVersion));
  }
  Fixed f;
  LODBAKE_RETURN_IF_ERROR(read_fixed(data + 1, size - 1, &f));
  if (f.base != base.vertex_count()) {
    return bad_compact(string_printf("base vertex count %u, but the base mesh has %zu vertices",
                                     f.base, base.vertex_count()));
  }
  const uint64_t r = f.splits;
  if (uint64_t{f.base} + r > UINT32_MAX)
    return bad_compact("base vertices and splits make more than 2^32 - 1 vertices");
  if (r != 0 && f.base < 2) return bad_compact("splits over a base of fewer than 2 vertices");
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
  for (const Triangle& t : base.triangles) {
    for (uint32_t v : t) {
      if (v >= base.vertex_count()) return bad_compact("a base triangle index is out of range");
    }
  }
  const bool with_vs = (f.flags & kVsplStoresVsPositions) != 0;
  const size_t per_split = with_vs ? 6 : 3;

  Bytes topology;
  Bytes positions;
  Bytes errors;
  BitWriter topology_out(&topology);
  BitWriter positions_out(&positions);
  ByteWriter errors_out(&errors);
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
    topology_out.write(vs, bits_for_count(n));
    topology_out.write(wing_value[0], bits_for_count(uint64_t{n} + 1));
    topology_out.write(wing_value[1], bits_for_count(uint64_t{n} + 1));
    if (f.quantized) {
      QuantizedPositions& qp = q.front();
      uint32_t value[6] = {};
      for (size_t c = 0; c < per_split; ++c) {
        const int a = static_cast<int>(c % 3);
        uint64_t z = 0;
        if (!read_golomb(&in, order[a], &z)) return bad_compact("stream ends inside a position");
        const uint32_t vl = wing_value[0] == n ? kNoVertex : wing_value[0];
        const uint32_t vr = wing_value[1] == n ? kNoVertex : wing_value[1];
        const int64_t predicted = c < 3 ? qp.predict_vt(vs, vl, vr, a) : int64_t{qp.get(vs, a)};
        const int64_t v = predicted + unzigzag(z);
        if (v < 0 || v > int64_t{qp.steps()}) {
          return bad_compact(string_printf(
              "split %u: position coordinate %" PRId64 " outside 0..%u", i, v, qp.steps()));
        }
        value[c] = static_cast<uint32_t>(v);
        positions_out.write(value[c], f.bits);
      }
      if (with_vs) {
        for (int a = 0; a < 3; ++a)
          qp.set(vs, a, value[3 + a]);
      }
      qp.append(value);
    }
    uint64_t z = 0;
    if (!read_golomb(&in, error_order, &z)) return bad_compact("stream ends inside an error");
    const int64_t bits = int64_t{previous} + unzigzag(z);
    if (bits < 0 || bits > int64_t{UINT32_MAX})
      return bad_compact(string_printf("split %u: error bits out of range", i));
    previous = static_cast<uint32_t>(bits);
    errors_out.write(previous);
    lists.split(vs, n, wing_value[0] == n ? kNoVertex : wing_value[0],
                wing_value[1] == n ? kNoVertex : wing_value[1]);
  }
  topology_out.finish();
  positions_out.finish();
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
  out.reserve(f.bytes + topology.size() + positions.size() + errors.size() + (size - pos));
  out.insert(out.end(), data + 1, data + 1 + f.bytes);
  out.insert(out.end(), topology.begin(), topology.end());
  const uint64_t float_bytes = f.quantized ? 0 : 12 * per_split / 3 * r;
  if (f.quantized) {
    out.insert(out.end(), positions.begin(), positions.end());
  } else {
    out.insert(out.end(), data + pos, data + pos + float_bytes);
  }
  out.insert(out.end(), errors.begin(), errors.end());
  out.insert(out.end(), data + pos + float_bytes, data + size);
  return out;
}

}  // namespace

Result<Bytes> encode_vspl_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base) {
  try {
    return encode_unchecked(raw, raw_size, base);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact VSPL");
  }
}

Result<Bytes> decode_vspl_compact(const uint8_t* data, size_t size, const TriangleMesh& base) {
  try {
    return decode_unchecked(data, size, base);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact VSPL");
  }
}

}  // namespace lodbake
