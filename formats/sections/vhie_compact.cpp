// Compact VHIE (codec 1): a lossless recoding of a raw VHIE payload, layout
// in docs/format.md "Compact VHIE". The balanced hierarchy of Kim, Lee and
// Kobbelt (2005) as lodbake stores it spends bits(L + 1) bits on each
// fundamental cut vertex, bits(L) on each leaf's input vertex and 16 bytes
// of float32 on each split.
//
// Choices, measured on the Stanford bunny's hierarchy (34819 splits, raw
// 178 bits per vertex):
// - Cut vertices are leaves near the split node: as the zigzag difference
//   of their leaf rank from the rank of the node's representative leaf
//   (reached by left children; it is the vertex the node stands for) the
//   mean log2 is 8.6 bits, against 16 raw.
// - Input vertices as differences from the previous leaf's: mesh files
//   number neighbouring vertices closely, and consecutive leaves are often
//   siblings (mean log2 8.5 against 16).
// - A split's position (its right child's) as the difference of each
//   coordinate's bit pattern from the node's own position: the right child
//   is the removed vertex, next to the survivor. A node's position is known
//   for every node below a right child (left children inherit theirs); the
//   few on the roots' left spines, whose positions are BASE's and not in the
//   payload, are predicted from the previous split's instead, so the codec
//   needs no other section.
// - Errors against the previous split's (against the parent's measured the
//   same: 23 bits of mean log2 difference; the mantissas are noise).
// - The structure bits stay one bit per node.
// The decoder only rebuilds the layout; decode_vhie() then checks the
// hierarchy as for any raw payload.
#include "formats/sections/vhie_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/vhie.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int { kCut, kInput, kPosition, kError, kContextCount };

Status bad_compact(const std::string& detail) {
  return malformed_section(kVhieTag, "compact: " + detail);
}

// A VHIE payload's values, in its own orders.
struct Fields {
  uint8_t fixed[kVhieFixedBytes] = {};
  uint32_t roots = 0;
  uint32_t nodes = 0;
  uint64_t splits = 0;
  uint64_t leaves = 0;
  std::vector<uint8_t> internal;    // per node
  std::vector<uint32_t> cuts;       // per split: left, right leaf rank (leaves = missing)
  std::vector<uint32_t> inputs;     // per leaf
  std::vector<uint32_t> positions;  // per split: x, y, z bit patterns
  std::vector<uint32_t> errors;     // per split: bit pattern
};

// What the predictions need from the structure: per split its node's
// representative leaf rank and the position predictor's source.
struct Shape {
  std::vector<uint32_t> representative;  // per split
  // Per split: the split whose stored position is this node's own position
  // (the nearest right-child step above it), or -1 on a root's left spine.
  std::vector<int64_t> own_position;
};

// Checks the structure (S ones, breadth first: children after their
// parent) and derives the shape. \return an error message, empty when fine.
std::string derive_shape(const Fields& f, Shape* shape) {
  uint64_t ones = 0;
  for (uint32_t i = 0; i < f.nodes; ++i) {
    if (f.internal[i] == 0) continue;
    if (uint64_t{f.roots} + 2 * ones <= i)
      return string_printf("node %u has children before itself", i);
    ++ones;
  }
  if (ones != f.splits)
    return string_printf("%" PRIu64 " internal nodes, the counts need %" PRIu64, ones, f.splits);
  std::vector<uint32_t> split_of(f.nodes, UINT32_MAX);  // node -> its split index
  std::vector<uint32_t> leaf_rank(f.nodes, 0);
  uint32_t k = 0, rank = 0;
  for (uint32_t i = 0; i < f.nodes; ++i) {
    if (f.internal[i] != 0) {
      split_of[i] = k++;
    } else {
      leaf_rank[i] = rank++;
    }
  }
  // Representatives bottom-up: children come after their parents.
  std::vector<uint32_t> rep(f.nodes, 0);
  for (uint32_t i = f.nodes; i-- > 0;) {
    rep[i] = f.internal[i] != 0 ? rep[f.roots + 2 * split_of[i]] : leaf_rank[i];
  }
  shape->representative.resize(f.splits);
  shape->own_position.assign(f.splits, -1);
  std::vector<int64_t> source(f.nodes, -1);  // per node, as own_position
  for (uint32_t i = 0; i < f.nodes; ++i) {
    if (f.internal[i] == 0) continue;
    const uint32_t s = split_of[i];
    const uint32_t child = f.roots + 2 * s;
    shape->representative[s] = rep[i];
    shape->own_position[s] = source[i];
    source[child] = source[i];
    source[child + 1] = s;
  }
  return {};
}

uint64_t difference(uint32_t value, uint32_t predicted) {
  return zigzag64(int64_t{value} - int64_t{predicted});
}

void encode_pass(const Fields& f, const Shape& shape, CompactStreamWriter* out) {
  for (uint8_t bit : f.internal)
    out->bits(bit, 1);
  const uint32_t missing = static_cast<uint32_t>(f.leaves);
  for (uint64_t s = 0; s < f.splits; ++s) {
    for (int side = 0; side < 2; ++side) {
      const uint32_t cut = f.cuts[2 * s + side];
      out->golomb(kCut, cut == missing ? 0 : 1 + difference(cut, shape.representative[s]));
    }
  }
  for (uint64_t j = 0; j < f.leaves; ++j)
    out->golomb(kInput, difference(f.inputs[j], j == 0 ? 0 : f.inputs[j - 1]));
  for (uint64_t s = 0; s < f.splits; ++s) {
    const int64_t from =
        shape.own_position[s] >= 0 ? shape.own_position[s] : static_cast<int64_t>(s) - 1;
    for (int a = 0; a < 3; ++a) {
      const uint32_t predicted = from < 0 ? 0 : f.positions[3 * static_cast<size_t>(from) + a];
      out->golomb(kPosition, difference(f.positions[3 * s + a], predicted));
    }
  }
  for (uint64_t s = 0; s < f.splits; ++s)
    out->golomb(kError, difference(f.errors[s], s == 0 ? 0 : f.errors[s - 1]));
}

Bytes write_raw(const Fields& f) {
  Bytes out(f.fixed, f.fixed + kVhieFixedBytes);
  BitWriter bits(&out);
  for (uint8_t bit : f.internal)
    bits.write(bit, 1);
  bits.finish();
  const int cut_bits = bits_for_count(f.leaves + 1);
  for (uint32_t cut : f.cuts)
    bits.write(cut, cut_bits);
  bits.finish();
  const int input_bits = bits_for_count(f.leaves);
  for (uint32_t input : f.inputs)
    bits.write(input, input_bits);
  bits.finish();
  ByteWriter bytes(&out);
  for (uint32_t p : f.positions)
    bytes.write(p);
  for (uint32_t e : f.errors)
    bytes.write(e);
  return out;
}

// The counts of the fixed fields (the raw reader's checks that need no
// payload size). \return an error message, empty when fine.
std::string read_fixed(const uint8_t* fixed, Fields* f) {
  std::memcpy(f->fixed, fixed, kVhieFixedBytes);
  std::memcpy(&f->roots, fixed, 4);
  std::memcpy(&f->nodes, fixed + 4, 4);
  if (f->nodes < f->roots || (f->nodes - f->roots) % 2 != 0 || f->nodes == UINT32_MAX)
    return string_printf("%u nodes cannot form full binary trees over %u roots", f->nodes,
                         f->roots);
  f->splits = (uint64_t{f->nodes} - f->roots) / 2;
  f->leaves = f->roots + f->splits;
  return {};
}

}  // namespace

Result<Bytes> encode_vhie_compact(const uint8_t* raw, size_t raw_size) {
  try {
    LODBAKE_RETURN_IF_ERROR(read_vhie_summary(raw, raw_size).status());
    Fields f;
    const std::string fixed_problem = read_fixed(raw, &f);
    if (!fixed_problem.empty()) return malformed_section(kVhieTag, fixed_problem);
    // read_vhie_summary() checked the exact size, so every part is there.
    const uint8_t* p = raw + kVhieFixedBytes;
    const size_t structure_bytes = static_cast<size_t>(packed_size_bytes(f.nodes, 1));
    const int cut_bits = bits_for_count(f.leaves + 1);
    const size_t cut_bytes = static_cast<size_t>(packed_size_bytes(2 * f.splits, cut_bits));
    const int input_bits = bits_for_count(f.leaves);
    const size_t input_bytes = static_cast<size_t>(packed_size_bytes(f.leaves, input_bits));
    BitReader structure(p, structure_bytes);
    BitReader cuts(p + structure_bytes, cut_bytes);
    BitReader inputs(p + structure_bytes + cut_bytes, input_bytes);
    uint32_t value = 0;
    f.internal.resize(f.nodes);
    for (uint32_t i = 0; i < f.nodes; ++i) {
      structure.read(1, &value);
      f.internal[i] = static_cast<uint8_t>(value);
    }
    f.cuts.resize(2 * f.splits);
    for (uint32_t& cut : f.cuts) {
      cuts.read(cut_bits, &cut);
      if (cut > f.leaves) return malformed_section(kVhieTag, "cut vertex out of range");
    }
    f.inputs.resize(f.leaves);
    for (uint32_t& input : f.inputs) {
      inputs.read(input_bits, &input);
      if (input >= f.leaves) return malformed_section(kVhieTag, "input vertex out of range");
    }
    const uint8_t* floats = p + structure_bytes + cut_bytes + input_bytes;
    f.positions.resize(3 * f.splits);
    f.errors.resize(f.splits);
    if (!f.positions.empty()) std::memcpy(f.positions.data(), floats, 12 * f.splits);
    if (!f.errors.empty()) std::memcpy(f.errors.data(), floats + 12 * f.splits, 4 * f.splits);
    Shape shape;
    const std::string problem = derive_shape(f, &shape);
    if (!problem.empty()) return malformed_section(kVhieTag, problem);
    Bytes out(f.fixed, f.fixed + kVhieFixedBytes);
    out.insert(out.begin(), kVhieCompactVersion);
    CompactStreamWriter stream(kContextCount);
    encode_pass(f, shape, &stream);
    stream.write_to(&out);
    // Nonzero padding bits in the raw streams are the one thing the values
    // do not capture: compare instead of checking each stream's tail.
    const Bytes again = write_raw(f);
    if (again.size() != raw_size || std::memcmp(again.data(), raw, raw_size) != 0)
      return unsupported(
          "VHIE payload has nonzero padding bits, which the compact codec cannot "
          "reproduce");
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact VHIE");
  }
}

Result<Bytes> decode_vhie_compact(const uint8_t* data, size_t size) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kVhieTag, data, size, kVhieFixedBytes, kVhieCompactVersion));
    Fields f;
    const std::string fixed_problem = read_fixed(data + 1, &f);
    if (!fixed_problem.empty()) return bad_compact(fixed_problem);
    CompactStreamReader in;
    if (!in.start(data + 1 + kVhieFixedBytes, size - 1 - kVhieFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // One structure bit per node, at least one bit per other code.
    const uint64_t min_bits = uint64_t{f.nodes} + 6 * f.splits + f.leaves;
    if (min_bits > in.bits_left()) {
      return bad_compact(string_printf("%u nodes need at least %" PRIu64 " bits, %" PRIu64
                                       " remain",
                                       f.nodes, min_bits, in.bits_left()));
    }
    uint64_t value = 0;
    f.internal.resize(f.nodes);
    for (uint32_t i = 0; i < f.nodes; ++i) {
      if (!in.bits(1, &value)) return bad_compact("truncated structure");
      f.internal[i] = static_cast<uint8_t>(value);
    }
    Shape shape;
    const std::string problem = derive_shape(f, &shape);
    if (!problem.empty()) return bad_compact(problem);
    auto predicted_plus = [](uint64_t code, uint32_t predicted, uint64_t limit,
                             uint32_t* out) -> bool {
      const int64_t v = int64_t{predicted} + unzigzag64(code);
      if (v < 0 || static_cast<uint64_t>(v) >= limit) return false;
      *out = static_cast<uint32_t>(v);
      return true;
    };
    f.cuts.resize(2 * f.splits);
    for (uint64_t s = 0; s < f.splits; ++s) {
      for (int side = 0; side < 2; ++side) {
        uint32_t& cut = f.cuts[2 * s + side];
        if (!in.golomb(kCut, &value)) return bad_compact("truncated cut vertices");
        if (value == 0) {
          cut = static_cast<uint32_t>(f.leaves);
        } else if (!predicted_plus(value - 1, shape.representative[s], f.leaves, &cut)) {
          return bad_compact(string_printf("split %" PRIu64 ": cut vertex out of range", s));
        }
      }
    }
    f.inputs.resize(f.leaves);
    for (uint64_t j = 0; j < f.leaves; ++j) {
      if (!in.golomb(kInput, &value) ||
          !predicted_plus(value, j == 0 ? 0 : f.inputs[j - 1], f.leaves, &f.inputs[j]))
        return bad_compact(string_printf("leaf %" PRIu64 ": bad input vertex code", j));
    }
    f.positions.resize(3 * f.splits);
    for (uint64_t s = 0; s < f.splits; ++s) {
      const int64_t from =
          shape.own_position[s] >= 0 ? shape.own_position[s] : static_cast<int64_t>(s) - 1;
      for (int a = 0; a < 3; ++a) {
        const uint32_t predicted = from < 0 ? 0 : f.positions[3 * static_cast<size_t>(from) + a];
        if (!in.golomb(kPosition, &value) ||
            !predicted_plus(value, predicted, uint64_t{1} << 32, &f.positions[3 * s + a]))
          return bad_compact(string_printf("split %" PRIu64 ": bad position code", s));
      }
    }
    f.errors.resize(f.splits);
    for (uint64_t s = 0; s < f.splits; ++s) {
      if (!in.golomb(kError, &value) ||
          !predicted_plus(value, s == 0 ? 0 : f.errors[s - 1], uint64_t{1} << 32, &f.errors[s]))
        return bad_compact(string_printf("split %" PRIu64 ": bad error code", s));
    }
    if (!in.at_clean_end())
      return bad_compact("nonzero padding or trailing bytes after the stream");
    // The fixed fields' own rules (flags, depth), so that what decodes is
    // what the encoder accepts.
    Bytes raw = write_raw(f);
    const Status fixed = read_vhie_summary(raw.data(), raw.size()).status();
    if (!fixed.is_ok()) return bad_compact(section_error_detail(fixed.message()));
    return raw;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact VHIE");
  }
}

}  // namespace lodbake
