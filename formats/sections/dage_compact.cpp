// Compact DAGE (codec 1): a lossless recoding of a raw DAGE payload, layout
// in docs/format.md "Compact DAGE". The split DAG of Zheng & Chan (2006)
// stores each node's parents as bits(N)-bit ids, strictly increasing and
// below the node.
//
// Choices, measured on the Stanford bunny's balanced hierarchy (34819
// nodes, 58891 parent links, raw 30 bits per vertex):
// - A node's parents from the highest down, as gaps: the node minus its
//   highest parent (mean log2 7.1 bits: a split depends on recent ones),
//   then each parent minus the next lower one (7.6), Exp-Golomb in a
//   context each, against 16 bits raw.
// - The parent count in a context of its own (1.3 bits of entropy).
// - The decoder rebuilds the DAG and writes it with the raw writer, so its
//   output obeys every DAGE rule; the encoder refuses raw payloads the raw
//   writer would not write byte for byte (another degree width).
#include "formats/sections/dage_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/dage.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int { kCount, kHighest, kGap, kContextCount };

Status bad_compact(const std::string& detail) {
  return malformed_section(kDageTag, "compact: " + detail);
}

void encode_pass(const VsplitDag& dag, CompactStreamWriter* out) {
  for (size_t i = 0; i < dag.node_count(); ++i) {
    const uint32_t a = dag.parent_offsets[i], z = dag.parent_offsets[i + 1];
    out->golomb(kCount, z - a);
    for (uint32_t k = z; k-- > a;) {
      const uint32_t above = k + 1 == z ? static_cast<uint32_t>(i) : dag.parents[k + 1];
      out->golomb(k + 1 == z ? kHighest : kGap, above - dag.parents[k] - 1);
    }
  }
}

}  // namespace

Result<Bytes> encode_dage_compact(const uint8_t* raw, size_t raw_size) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(VsplitDag dag, decode_dage(raw, raw_size));
    LODBAKE_ASSIGN_OR_RETURN(Bytes canonical, encode_dage(dag));
    LODBAKE_RETURN_IF_ERROR(
        require_canonical_layout(kDageTag, canonical, raw, raw_size, "degree width"));
    Bytes out(1 + kDageFixedBytes);
    out[0] = kDageCompactVersion;
    std::memcpy(out.data() + 1, raw, kDageFixedBytes);
    CompactStreamWriter stream(kContextCount);
    encode_pass(dag, &stream);
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact DAGE");
  }
}

Result<Bytes> decode_dage_compact(const uint8_t* data, size_t size) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kDageTag, data, size, kDageFixedBytes, kDageCompactVersion));
    const uint8_t* fixed = data + 1;
    uint32_t node_count = 0, base_vertices = 0, edge_count = 0;
    std::memcpy(&node_count, fixed, 4);
    std::memcpy(&base_vertices, fixed + 4, 4);
    std::memcpy(&edge_count, fixed + 8, 4);
    CompactStreamReader in;
    if (!in.start(fixed + kDageFixedBytes, size - 1 - kDageFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // Every node's count and every parent's gap take at least one bit.
    if (uint64_t{node_count} + edge_count > in.bits_left()) {
      return bad_compact(
          string_printf("%u nodes and %u parents need at least as many bits, %" PRIu64 " remain",
                        node_count, edge_count, in.bits_left()));
    }
    VsplitDag dag;
    dag.base_vertex_count = base_vertices;
    dag.parent_offsets.reserve(uint64_t{node_count} + 1);
    dag.parents.resize(edge_count);
    uint64_t value = 0;
    size_t filled = 0;
    for (uint32_t i = 0; i < node_count; ++i) {
      if (!in.golomb(kCount, &value))
        return bad_compact(string_printf("node %u: truncated parent count", i));
      if (value > i || value > edge_count - filled)
        return bad_compact(string_printf("node %u: %" PRIu64 " parents", i, value));
      const size_t a = filled, z = filled + static_cast<size_t>(value);
      int64_t above = i;
      for (size_t k = z; k-- > a;) {
        if (!in.golomb(k + 1 == z ? kHighest : kGap, &value))
          return bad_compact(string_printf("node %u: truncated parent gap", i));
        const int64_t parent =
            above - 1 - static_cast<int64_t>(value > UINT32_MAX ? UINT32_MAX : value);
        if (parent < 0) return bad_compact(string_printf("node %u: parent below 0", i));
        dag.parents[k] = static_cast<uint32_t>(parent);
        above = parent;
      }
      filled = z;
      dag.parent_offsets.push_back(static_cast<uint32_t>(filled));
    }
    if (filled != edge_count)
      return bad_compact(string_printf("%zu parents, the header says %u", filled, edge_count));
    return finish_compact_decode(kDageTag, in, encode_dage(dag), fixed, kDageFixedBytes, "DAG");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact DAGE");
  }
}

}  // namespace lodbake
