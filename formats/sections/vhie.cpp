// VHIE section codec and the structural checks of a balanced vertex
// hierarchy (Kim, Lee and Kobbelt 2005, sections 4, 6.1, 6.2); byte layout
// in docs/format.md "VHIE". Choices:
// - the tree structure is one bit per node in breadth-first order (1: has
//   two children); since children are appended in parent order, the bits
//   alone give every parent and child index and every heap id, so neither
//   is stored;
// - fundamental cut vertices are leaf ranks (leaves numbered in array
//   order) in bits(L + 1), the value L meaning "no wing": the rank is what a
//   reader indexes, and a <tree-id, node-id> follows from it;
// - positions: a left child sits at its parent's position (half-edge
//   collapse), so only the right child of each split is stored (float32, as
//   the paper's vsplit packet stores only v_u); the roots' come from BASE;
// - all counts are fixed by root count, node count and the structure bits,
//   so the exact payload size is checked before the per-node arrays are
//   allocated.
#include "formats/sections/vhie.h"

#include <cmath>
#include <cstring>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

Status bad_vhie(const std::string& detail) {
  return malformed_section(kVhieTag, detail);
}

bool finite3(const Vec3f& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

uint32_t levels_of(const VertexHierarchy& h) {
  std::vector<uint32_t> level(h.node_count(), 1);
  uint32_t depth = h.node_count() == 0 ? 0 : 1;
  for (size_t i = 0; i < h.node_count(); ++i) {
    if (h.parent[i] != kNoNode) level[i] = level[h.parent[i]] + 1;
    depth = std::max(depth, level[i]);
  }
  return depth;
}

}  // namespace

std::vector<HierarchyNodeId> hierarchy_node_ids(const VertexHierarchy& h) {
  std::vector<HierarchyNodeId> ids(h.node_count());
  for (uint32_t i = 0; i < h.node_count(); ++i) {
    if (h.parent[i] == kNoNode) {
      ids[i] = {i, 1};
      continue;
    }
    const HierarchyNodeId& p = ids[h.parent[i]];
    const uint64_t bit = i == h.first_child[h.parent[i]] ? 0 : 1;
    ids[i] = {p.tree, (p.heap << 1) | bit};
  }
  return ids;
}

HierarchyShape hierarchy_shape(const VertexHierarchy& h) {
  HierarchyShape s;
  s.nodes = h.node_count();
  s.roots = h.root_count();
  s.splits = (s.nodes - s.roots) / 2;
  s.leaves = s.roots + s.splits;
  s.depth = levels_of(h);
  s.tree_bits = bits_for_count(s.roots);
  s.id_bits = s.tree_bits + static_cast<int>(s.depth);
  s.id_bytes = s.id_bits <= 32 ? 4 : 8;
  return s;
}

std::vector<std::string> validate_hierarchy(const VertexHierarchy& h) {
  std::vector<std::string> out;
  const size_t n = h.parent.size();
  const size_t roots = h.root_count();
  if (h.first_child.size() != n || h.position.size() != n || h.cut_left.size() != n ||
      h.cut_right.size() != n || h.input_vertex.size() != n || h.error.size() != n) {
    out.push_back("per-node arrays differ in size (" + std::to_string(n) + " parents)");
    return out;
  }
  if (n >= kNoNode) {
    out.push_back("more than 2^32 - 2 nodes");
    return out;
  }
  if (roots > n) {
    out.push_back("base mesh has " + std::to_string(roots) + " vertices but the hierarchy " +
                  std::to_string(n) + " nodes");
    return out;
  }
  // Breadth-first packing: replaying the child pointers in order must
  // reproduce them.
  uint64_t next = roots;
  for (size_t i = 0; i < n; ++i) {
    const bool root = i < roots;
    if (root != (h.parent[i] == kNoNode)) {
      out.push_back("node " + std::to_string(i) + ": only the first " + std::to_string(roots) +
                    " nodes are roots");
      return out;
    }
    if (!root && h.parent[i] >= i) {
      out.push_back("node " + std::to_string(i) + ": parent index " + std::to_string(h.parent[i]) +
                    " is not below its own");
      return out;
    }
    if (h.first_child[i] == kNoNode) continue;
    if (h.first_child[i] != next || next + 2 > n) {
      out.push_back("node " + std::to_string(i) + ": children at " +
                    std::to_string(h.first_child[i]) + ", breadth-first order puts them at " +
                    std::to_string(next));
      return out;
    }
    if (h.parent[next] != i || h.parent[next + 1] != i) {
      out.push_back("node " + std::to_string(i) + ": its children name another parent");
      return out;
    }
    next += 2;
  }
  if (next != n) {
    out.push_back(std::to_string(n - next) + " nodes are in no tree");
    return out;
  }
  if (levels_of(h) > 64) out.push_back("a tree has more than 64 levels (heap ids above 64 bits)");

  size_t leaves = 0;
  uint64_t bad_cut = 0, bad_inside = 0, no_wing = 0, bad_pos = 0, bad_left = 0, bad_err = 0;
  uint64_t first_cut = 0, first_inside = 0;
  std::vector<uint8_t> seen;
  uint64_t bad_input = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!finite3(h.position[i])) ++bad_pos;
    if (!std::isfinite(h.error[i]) || h.error[i] < 0) ++bad_err;
    if (h.first_child[i] == kNoNode) {
      ++leaves;
      continue;
    }
    if (h.position[h.first_child[i]] != h.position[i]) ++bad_left;
    if (h.cut_left[i] == kNoNode && h.cut_right[i] == kNoNode) ++no_wing;
    for (uint32_t c : {h.cut_left[i], h.cut_right[i]}) {
      if (c == kNoNode) continue;
      if (c >= n || h.first_child[c] != kNoNode) {
        if (bad_cut++ == 0) first_cut = i;
        continue;
      }
      // Outside the node's own subtree, or ActiveAncestor would be the node.
      uint32_t a = c;
      uint32_t steps = 0;
      while (a != kNoNode && a != i && steps++ <= 64)
        a = h.parent[a];
      if (a == i && bad_inside++ == 0) first_inside = i;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (h.first_child[i] != kNoNode) {
      if (h.input_vertex[i] != kNoVertex) ++bad_input;
      continue;
    }
    const uint32_t v = h.input_vertex[i];
    if (seen.empty()) seen.assign(leaves, 0);
    if (v >= leaves || seen[v]) {
      ++bad_input;
      continue;
    }
    seen[v] = 1;
  }
  if (bad_cut) {
    out.push_back(std::to_string(bad_cut) +
                  " fundamental cut vertices are not leaves (first at node " +
                  std::to_string(first_cut) + ")");
  }
  if (bad_inside) {
    out.push_back(std::to_string(bad_inside) +
                  " fundamental cut vertices lie in their own node's subtree (first at node " +
                  std::to_string(first_inside) + ")");
  }
  if (no_wing) out.push_back(std::to_string(no_wing) + " splits have neither cut vertex");
  if (bad_input) {
    out.push_back("input_vertex is not a permutation over the " + std::to_string(leaves) +
                  " leaves (" + std::to_string(bad_input) + " bad entries)");
  }
  if (bad_pos) out.push_back(std::to_string(bad_pos) + " nodes have a non-finite position");
  if (bad_left) {
    out.push_back(std::to_string(bad_left) + " left children are not at their parent's position");
  }
  if (bad_err)
    out.push_back(std::to_string(bad_err) + " nodes have a negative or non-finite error");
  for (size_t r = 0; r < roots && bad_pos == 0; ++r) {
    if (h.base.positions[r] != h.position[r]) {
      out.push_back("root " + std::to_string(r) + " is not at its base vertex's position");
      break;
    }
  }
  return out;
}

Result<Bytes> encode_vhie(const VertexHierarchy& h) {
  const std::vector<std::string> problems = validate_hierarchy(h);
  if (!problems.empty()) return invalid_input("cannot encode VHIE: " + problems.front());
  try {
    const HierarchyShape shape = hierarchy_shape(h);
    Bytes out;
    ByteWriter w(&out);
    w.write(static_cast<uint32_t>(shape.roots));
    w.write(static_cast<uint32_t>(shape.nodes));
    w.write(static_cast<uint8_t>(shape.depth));
    w.write(uint8_t{0});
    w.write(uint16_t{0});
    BitWriter bits(&out);
    for (size_t i = 0; i < shape.nodes; ++i)
      bits.write(h.first_child[i] == kNoNode ? 0 : 1, 1);
    bits.finish();
    std::vector<uint32_t> leaf_rank(shape.nodes, 0);
    uint32_t rank = 0;
    for (size_t i = 0; i < shape.nodes; ++i) {
      if (h.first_child[i] == kNoNode) leaf_rank[i] = rank++;
    }
    const int cut_bits = bits_for_count(shape.leaves + 1);
    const auto none = static_cast<uint32_t>(shape.leaves);
    for (size_t i = 0; i < shape.nodes; ++i) {
      if (h.first_child[i] == kNoNode) continue;
      bits.write(h.cut_left[i] == kNoNode ? none : leaf_rank[h.cut_left[i]], cut_bits);
      bits.write(h.cut_right[i] == kNoNode ? none : leaf_rank[h.cut_right[i]], cut_bits);
    }
    bits.finish();
    const int input_bits = bits_for_count(shape.leaves);
    for (size_t i = 0; i < shape.nodes; ++i) {
      if (h.first_child[i] == kNoNode) bits.write(h.input_vertex[i], input_bits);
    }
    bits.finish();
    for (size_t i = 0; i < shape.nodes; ++i) {
      if (h.first_child[i] == kNoNode) continue;
      const Vec3f& p = h.position[h.first_child[i] + 1];
      for (float c : p)
        w.write(c);
    }
    for (size_t i = 0; i < shape.nodes; ++i) {
      if (h.first_child[i] != kNoNode) w.write(h.error[i]);
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding VHIE");
  }
}

Result<VhieSummary> read_vhie_summary(const uint8_t* data, size_t size) {
  ByteReader r(data, size);
  VhieSummary s;
  uint16_t reserved = 0;
  uint8_t depth = 0;
  if (!r.read(&s.root_count) || !r.read(&s.node_count) || !r.read(&depth) || !r.read(&s.flags) ||
      !r.read(&reserved)) {
    return bad_vhie("payload of " + std::to_string(size) + " bytes is shorter than the " +
                    std::to_string(kVhieFixedBytes) + "-byte header");
  }
  s.depth = depth;
  if (s.flags != 0 || reserved != 0) return bad_vhie("unknown flags or nonzero reserved field");
  if (s.node_count < s.root_count || (s.node_count - s.root_count) % 2 != 0) {
    return bad_vhie(std::to_string(s.node_count) + " nodes cannot form full binary trees over " +
                    std::to_string(s.root_count) + " roots");
  }
  if (s.node_count >= kNoNode) return bad_vhie("node count is too large");
  if (s.depth > 64) return bad_vhie("depth " + std::to_string(s.depth) + " is above 64 levels");
  if (s.node_count > 0 && s.depth == 0) return bad_vhie("depth 0 with nodes");
  // Exact payload size: everything follows from the counts.
  const uint64_t splits = (uint64_t{s.node_count} - s.root_count) / 2;
  const uint64_t leaves = s.root_count + splits;
  const uint64_t need = kVhieFixedBytes + packed_size_bytes(s.node_count, 1) +
                        packed_size_bytes(2 * splits, bits_for_count(leaves + 1)) +
                        packed_size_bytes(leaves, bits_for_count(leaves)) + splits * 16;
  if (need != size) {
    return bad_vhie("payload has " + std::to_string(size) + " bytes, its counts need " +
                    std::to_string(need));
  }
  return s;
}

Result<VertexHierarchy> decode_vhie(const uint8_t* data, size_t size, TriangleMesh base) {
  LODBAKE_ASSIGN_OR_RETURN(VhieSummary s, read_vhie_summary(data, size));
  if (s.root_count != base.positions.size()) {
    return bad_vhie("root count " + std::to_string(s.root_count) + " differs from BASE's " +
                    std::to_string(base.positions.size()) + " vertices");
  }
  try {
    const size_t n = s.node_count;
    const size_t roots = s.root_count;
    const size_t splits = (n - roots) / 2;
    const size_t leaves = roots + splits;
    VertexHierarchy h;
    h.parent.assign(n, kNoNode);
    h.first_child.assign(n, kNoNode);
    h.position.assign(n, Vec3f{});
    h.cut_left.assign(n, kNoNode);
    h.cut_right.assign(n, kNoNode);
    h.input_vertex.assign(n, kNoVertex);
    h.error.assign(n, 0.0f);
    size_t pos = kVhieFixedBytes;
    const size_t structure_bytes = packed_size_bytes(n, 1);
    BitReader structure(data + pos, structure_bytes);
    uint64_t next = roots;
    std::vector<uint8_t> level(n, 1);
    uint32_t depth = n == 0 ? 0 : 1;
    for (size_t i = 0; i < n; ++i) {
      uint32_t bit = 0;
      structure.read(1, &bit);
      if (i >= next) return bad_vhie("node " + std::to_string(i) + " is in no tree");
      if (!bit) continue;
      if (next + 2 > n) {
        return bad_vhie("node " + std::to_string(i) + " has children past the " +
                        std::to_string(n) + " nodes");
      }
      h.first_child[i] = static_cast<uint32_t>(next);
      h.parent[next] = h.parent[next + 1] = static_cast<uint32_t>(i);
      if (level[i] >= 64) return bad_vhie("a tree has more than 64 levels");
      level[next] = level[next + 1] = static_cast<uint8_t>(level[i] + 1);
      depth = std::max<uint32_t>(depth, level[i] + 1u);
      next += 2;
    }
    if (next != n)
      return bad_vhie("the structure bits describe " + std::to_string(next) +
                      " nodes, the header " + std::to_string(n));
    if (!structure.padding_is_zero()) return bad_vhie("nonzero padding after the structure bits");
    if (depth != s.depth) {
      return bad_vhie("stored depth " + std::to_string(s.depth) + ", the trees have " +
                      std::to_string(depth) + " levels");
    }
    pos += structure_bytes;
    std::vector<uint32_t> leaf_node;
    leaf_node.reserve(leaves);
    for (size_t i = 0; i < n; ++i) {
      if (h.first_child[i] == kNoNode) leaf_node.push_back(static_cast<uint32_t>(i));
    }
    const int cut_bits = bits_for_count(leaves + 1);
    const size_t cut_bytes = packed_size_bytes(2 * splits, cut_bits);
    BitReader cuts(data + pos, cut_bytes);
    for (size_t i = 0; i < n; ++i) {
      if (h.first_child[i] == kNoNode) continue;
      uint32_t l = 0, r = 0;
      cuts.read(cut_bits, &l);
      cuts.read(cut_bits, &r);
      if (l > leaves || r > leaves) {
        return bad_vhie("node " + std::to_string(i) + ": cut vertex out of range (" +
                        std::to_string(leaves) + " leaves)");
      }
      if (l == leaves && r == leaves) {
        return bad_vhie("node " + std::to_string(i) + ": both cut vertices are missing");
      }
      h.cut_left[i] = l == leaves ? kNoNode : leaf_node[l];
      h.cut_right[i] = r == leaves ? kNoNode : leaf_node[r];
    }
    if (!cuts.padding_is_zero()) return bad_vhie("nonzero padding after the cut vertices");
    pos += cut_bytes;
    const int input_bits = bits_for_count(leaves);
    const size_t input_bytes = packed_size_bytes(leaves, input_bits);
    BitReader input(data + pos, input_bytes);
    std::vector<uint8_t> seen(leaves, 0);
    for (uint32_t node : leaf_node) {
      uint32_t v = 0;
      input.read(input_bits, &v);
      if (v >= leaves || seen[v]) {
        return bad_vhie("input vertex " + std::to_string(v) + " of node " + std::to_string(node) +
                        " is out of range or repeated");
      }
      seen[v] = 1;
      h.input_vertex[node] = v;
    }
    if (!input.padding_is_zero()) return bad_vhie("nonzero padding after the input vertices");
    pos += input_bytes;
    for (size_t r = 0; r < roots; ++r)
      h.position[r] = base.positions[r];
    ByteReader rest(data + pos, size - pos);
    for (size_t i = 0; i < n; ++i) {
      if (h.first_child[i] == kNoNode) continue;
      Vec3f p{};
      rest.read(&p[0]);
      rest.read(&p[1]);
      rest.read(&p[2]);
      if (!finite3(p)) return bad_vhie("node " + std::to_string(i) + ": non-finite position");
      h.position[h.first_child[i]] = h.position[i];
      h.position[h.first_child[i] + 1] = p;
    }
    for (size_t i = 0; i < n; ++i) {
      if (h.first_child[i] == kNoNode) continue;
      float e = 0;
      rest.read(&e);
      if (!std::isfinite(e) || e < 0) {
        return bad_vhie("node " + std::to_string(i) + ": negative or non-finite error");
      }
      h.error[i] = e;
    }
    h.base = std::move(base);
    const std::vector<std::string> problems = validate_hierarchy(h);
    if (!problems.empty()) return bad_vhie(problems.front());
    return h;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding VHIE");
  }
}

}  // namespace lodbake
