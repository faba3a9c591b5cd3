// DAGE section codec: the DAG of vertex splits (Zheng & Chan 2006, section
// 3), byte layout in docs/format.md "DAGE".
//
// Choices:
// - Node i is split i, and split order is a topological order, so parents
//   are stored below their node and strictly increasing: acyclicity and
//   uniqueness are layout rules a reader checks record by record.
// - Parent counts take a fixed width of at least one bit, which bounds the
//   node count by the payload size before the offsets are allocated.
//   Parent indices take bits(N); the graph is sparse and its indices are
//   spread over the whole split order (a split's parents are its
//   neighbourhood's last changes), so deltas would not be small.
// - Children are not stored: they are the parents' transpose.
// - The root and leaf counts are the sizes of Fs at the base mesh and of Fc
//   at the full mesh; a reader checks them against the graph, so a wrong
//   degree or parent shows up even where the layout rules hold.
#include "formats/sections/dage.h"

#include <algorithm>
#include <cinttypes>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_dage(const std::string& detail) {
  return malformed_section(kDageTag, detail);
}

// The first structural problem of a DAG, or "".
std::string structure_problem(const VsplitDag& dag) {
  const size_t n = dag.node_count();
  if (dag.parent_offsets.empty() || dag.parent_offsets[0] != 0 ||
      dag.parent_offsets.back() != dag.parents.size()) {
    return "parent offsets do not span the parent list";
  }
  if (n >= UINT32_MAX || dag.parents.size() >= UINT32_MAX)
    return "more than 2^32 - 2 nodes or edges";
  for (size_t i = 0; i < n; ++i) {
    const uint32_t b = dag.parent_offsets[i];
    const uint32_t e = dag.parent_offsets[i + 1];
    if (e < b) return string_printf("parent offsets decrease at node %zu", i);
    for (uint32_t k = b; k < e; ++k) {
      if (dag.parents[k] >= i) {
        return string_printf("node %zu has parent %u, parents must be below their node", i,
                             dag.parents[k]);
      }
      if (k > b && dag.parents[k] <= dag.parents[k - 1]) {
        return string_printf("node %zu: parents %u, %u are not strictly increasing", i,
                             dag.parents[k - 1], dag.parents[k]);
      }
    }
  }
  return "";
}

void count_roots_and_leaves(const VsplitDag& dag, uint32_t* roots, uint32_t* leaves) {
  const size_t n = dag.node_count();
  std::vector<uint8_t> has_child(n, 0);
  for (uint32_t p : dag.parents)
    has_child[p] = 1;
  *roots = 0;
  *leaves = 0;
  for (size_t i = 0; i < n; ++i) {
    *roots += dag.parent_offsets[i + 1] == dag.parent_offsets[i];
    *leaves += has_child[i] == 0;
  }
}

uint8_t degree_width(const VsplitDag& dag) {
  uint32_t max_degree = 0;
  for (size_t i = 0; i < dag.node_count(); ++i)
    max_degree = std::max(max_degree, dag.parent_offsets[i + 1] - dag.parent_offsets[i]);
  return static_cast<uint8_t>(std::max(1, bits_for_count(uint64_t{max_degree} + 1)));
}

Status parse_fixed(const uint8_t* data, size_t size, DageSummary* s) {
  ByteReader reader(data, size);
  uint16_t reserved = 0;
  if (!reader.read(&s->node_count) || !reader.read(&s->base_vertex_count) ||
      !reader.read(&s->edge_count) || !reader.read(&s->root_count) ||
      !reader.read(&s->leaf_count) || !reader.read(&s->degree_bits) ||
      !reader.read(&s->parent_bits) || !reader.read(&reserved)) {
    return bad_dage(
        string_printf("payload has %zu bytes, the fixed fields need %zu", size, kDageFixedBytes));
  }
  if (reserved != 0) return bad_dage(string_printf("reserved field is %u, must be 0", reserved));
  const uint64_t n = s->node_count;
  if (n == UINT32_MAX) return bad_dage("node count 2^32 - 1 is too large");
  if (n == 0 ? s->degree_bits != 0 : (s->degree_bits < 1 || s->degree_bits > 32)) {
    return bad_dage(
        string_printf("degree bits %u, must be 1..32 (0 without nodes)", s->degree_bits));
  }
  if (s->parent_bits != bits_for_count(n)) {
    return bad_dage(string_printf("parent bits %u, %u nodes need %d", s->parent_bits, s->node_count,
                                  bits_for_count(n)));
  }
  if (n <= 1 && s->edge_count != 0) {
    return bad_dage(string_printf("%u edges between %u nodes", s->edge_count, s->node_count));
  }
  if (s->root_count > n || s->leaf_count > n ||
      (n > 0 && (s->root_count == 0 || s->leaf_count == 0))) {
    return bad_dage(string_printf("%u roots and %u leaves for %u nodes", s->root_count,
                                  s->leaf_count, s->node_count));
  }
  const uint64_t bits = n * s->degree_bits + uint64_t{s->edge_count} * s->parent_bits;
  const uint64_t bytes = (bits + 7) / 8;
  if (bytes != reader.remaining()) {
    return bad_dage(string_printf("%u nodes and %u edges need %" PRIu64
                                  " bytes after the fixed fields, %zu follow",
                                  s->node_count, s->edge_count, bytes, reader.remaining()));
  }
  return Status::ok();
}

}  // namespace

Result<Bytes> encode_dage(const VsplitDag& dag) {
  try {
    const std::string problem = structure_problem(dag);
    if (!problem.empty()) return invalid_input("cannot encode DAGE: " + problem);
    const uint32_t n = static_cast<uint32_t>(dag.node_count());
    DageSummary s;
    s.node_count = n;
    s.base_vertex_count = dag.base_vertex_count;
    s.edge_count = static_cast<uint32_t>(dag.edge_count());
    count_roots_and_leaves(dag, &s.root_count, &s.leaf_count);
    s.degree_bits = n == 0 ? 0 : degree_width(dag);
    s.parent_bits = static_cast<uint8_t>(bits_for_count(n));
    Bytes out;
    ByteWriter writer(&out);
    writer.write(s.node_count);
    writer.write(s.base_vertex_count);
    writer.write(s.edge_count);
    writer.write(s.root_count);
    writer.write(s.leaf_count);
    writer.write(s.degree_bits);
    writer.write(s.parent_bits);
    writer.write(uint16_t{0});
    BitWriter bits(&out);
    for (uint32_t i = 0; i < n; ++i)
      bits.write(dag.parent_offsets[i + 1] - dag.parent_offsets[i], s.degree_bits);
    for (uint32_t p : dag.parents)
      bits.write(p, s.parent_bits);
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding DAGE");
  }
}

Result<DageSummary> read_dage_summary(const uint8_t* data, size_t size) {
  DageSummary s;
  LODBAKE_RETURN_IF_ERROR(parse_fixed(data, size, &s));
  return s;
}

Result<VsplitDag> decode_dage(const uint8_t* data, size_t size, DageSummary* summary) {
  try {
    DageSummary s;
    LODBAKE_RETURN_IF_ERROR(parse_fixed(data, size, &s));
    BitReader in(data + kDageFixedBytes, size - kDageFixedBytes);
    VsplitDag dag;
    dag.base_vertex_count = s.base_vertex_count;
    // parse_fixed() tied N (>= 1 bit each) and E to the payload size.
    dag.parent_offsets.resize(size_t{s.node_count} + 1);
    uint64_t total = 0;
    for (uint32_t i = 0; i < s.node_count; ++i) {
      uint32_t degree = 0;
      if (!in.read(s.degree_bits, &degree)) return bad_dage("degree stream too short");
      if (degree > i) {
        return bad_dage(
            string_printf("node %u has %u parents, only %u nodes precede it", i, degree, i));
      }
      total += degree;
      if (total > s.edge_count) {
        return bad_dage(
            string_printf("the parent counts exceed the %u edges at node %u", s.edge_count, i));
      }
      dag.parent_offsets[i + 1] = static_cast<uint32_t>(total);
    }
    if (total != s.edge_count) {
      return bad_dage(string_printf(
          "the parent counts sum to %" PRIu64 ", the header says %u edges", total, s.edge_count));
    }
    dag.parents.resize(s.edge_count);
    for (uint32_t i = 0; i < s.node_count; ++i) {
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k) {
        if (!in.read(s.parent_bits, &dag.parents[k])) return bad_dage("parent stream too short");
        if (dag.parents[k] >= i ||
            (k > dag.parent_offsets[i] && dag.parents[k] <= dag.parents[k - 1])) {
          return bad_dage(string_printf(
              "node %u: parent %u is not below the node or not above the previous parent", i,
              dag.parents[k]));
        }
      }
    }
    if (!in.padding_is_zero()) return bad_dage("nonzero padding bits after the parents");
    uint32_t roots = 0;
    uint32_t leaves = 0;
    count_roots_and_leaves(dag, &roots, &leaves);
    if (roots != s.root_count || leaves != s.leaf_count) {
      return bad_dage(
          string_printf("the header counts %u roots and %u leaves, the graph has %u and %u",
                        s.root_count, s.leaf_count, roots, leaves));
    }
    if (summary != nullptr) *summary = s;
    return dag;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding DAGE");
  }
}

std::vector<std::string> validate_dage(const VsplitDag& dag) {
  std::vector<std::string> findings;
  try {
    const std::string problem = structure_problem(dag);
    if (!problem.empty()) return {problem};
    const size_t n = dag.node_count();
    // Redundant edges: visiting parents from the highest down, mark the
    // ancestors (above the lowest parent) of each one not yet marked; a
    // marked parent is implied by a higher one.
    std::vector<uint32_t> mark(n, UINT32_MAX);
    std::vector<uint32_t> stack;
    uint64_t redundant = 0;
    std::string first;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t node = static_cast<uint32_t>(i);
      const uint32_t b = dag.parent_offsets[i];
      const uint32_t e = dag.parent_offsets[i + 1];
      if (b == e) continue;
      const uint32_t lowest = dag.parents[b];
      for (uint32_t k = e; k-- > b;) {
        const uint32_t q = dag.parents[k];
        if (mark[q] == node) {
          if (redundant++ == 0) first = string_printf("node %zu's parent %u", i, q);
          continue;
        }
        stack.assign(1, q);
        while (!stack.empty()) {
          const uint32_t v = stack.back();
          stack.pop_back();
          for (uint32_t j = dag.parent_offsets[v]; j < dag.parent_offsets[v + 1]; ++j) {
            const uint32_t p = dag.parents[j];
            if (p < lowest || mark[p] == node) continue;
            mark[p] = node;
            stack.push_back(p);
          }
        }
      }
    }
    if (redundant != 0) {
      findings.push_back(string_printf("%" PRIu64 " edges are implied by others (first: %s)",
                                       redundant, first.c_str()));
    }

    // Counters: a collapsed node's counts its collapsed parents, a split
    // node's its split children (Zheng & Chan, section 3).
    std::vector<uint32_t> child_offsets(n + 1, 0);
    for (uint32_t p : dag.parents)
      ++child_offsets[p + 1];
    for (size_t i = 0; i < n; ++i)
      child_offsets[i + 1] += child_offsets[i];
    std::vector<uint32_t> children(dag.parents.size());
    std::vector<uint32_t> fill(child_offsets.begin(), child_offsets.end() - 1);
    for (size_t i = 0; i < n; ++i) {
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k)
        children[fill[dag.parents[k]]++] = static_cast<uint32_t>(i);
    }
    std::vector<uint32_t> counter(n);
    for (size_t i = 0; i < n; ++i)
      counter[i] = dag.parent_offsets[i + 1] - dag.parent_offsets[i];
    uint64_t not_legal = 0;
    for (size_t i = 0; i < n; ++i) {  // split all in node order
      if (counter[i] != 0) ++not_legal;
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k)
        ++counter[dag.parents[k]];
      for (uint32_t k = child_offsets[i]; k < child_offsets[i + 1]; ++k)
        --counter[children[k]];
      counter[i] = 0;
    }
    for (size_t i = n; i-- > 0;) {  // collapse all back
      if (counter[i] != 0) ++not_legal;
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k)
        --counter[dag.parents[k]];
      for (uint32_t k = child_offsets[i]; k < child_offsets[i + 1]; ++k)
        ++counter[children[k]];
      counter[i] = 0;
    }
    uint64_t wrong_end = 0;
    for (size_t i = 0; i < n; ++i)
      wrong_end += counter[i] != dag.parent_offsets[i + 1] - dag.parent_offsets[i];
    if (not_legal != 0 || wrong_end != 0) {
      findings.push_back(string_printf("front counters inconsistent: %" PRIu64
                                       " nodes not legal when reached, %" PRIu64
                                       " counters not back to their parent count",
                                       not_legal, wrong_end));
    }
  } catch (const std::bad_alloc&) {
    findings.push_back("out of memory while validating DAGE");
  }
  return findings;
}

}  // namespace lodbake
