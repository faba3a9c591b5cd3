// The VHIE section: a balanced vertex hierarchy (formats/mesh/
// vertex_hierarchy.h) over the base mesh in BASE: tree structure in
// breadth-first order, fundamental cut vertices, the removed vertices'
// positions, collapse errors and the leaves' input vertices. A container
// holding one has BASE + VHIE (+ RFIN, + META). Byte layout: docs/format.md
// "VHIE". Also the structural checks and <tree-id, node-id> arithmetic every
// user of a hierarchy needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The bytes before the bit streams.
inline constexpr size_t kVhieFixedBytes = 12;

/// Counts of a hierarchy and the bits of its ids.
struct HierarchyShape {
  uint64_t nodes = 0;
  uint64_t roots = 0;
  uint64_t leaves = 0;  ///< = input vertices
  uint64_t splits = 0;  ///< internal nodes
  uint32_t depth = 0;   ///< levels of the deepest tree (a lone root: 1) = node-id bits
  int tree_bits = 0;    ///< ceil(log2 #roots)
  int id_bits = 0;      ///< tree_bits + depth
  int id_bytes = 0;     ///< 4 when id_bits <= 32, else 8
};

/// The fixed fields of a VHIE payload.
struct VhieSummary {
  uint32_t root_count = 0;
  uint32_t node_count = 0;
  uint32_t depth = 0;
  uint8_t flags = 0;
};

/// <tree-id, node-id> of every node. \pre validate_hierarchy(h) is empty.
std::vector<HierarchyNodeId> hierarchy_node_ids(const VertexHierarchy& h);

/// Counts and id bits. \pre validate_hierarchy(h) is empty.
HierarchyShape hierarchy_shape(const VertexHierarchy& h);

/// Structural checks (`lodbake-inspect --validate`): array sizes, roots =
/// base vertices, breadth-first packing (parent index below the child's,
/// children adjacent and in order), heap ids within 64 bits, fundamental cut
/// vertices that are leaves outside the node's own subtree, not both missing,
/// input_vertex a permutation over the leaves, finite positions, a left child
/// at its parent's position (half-edge collapses), finite non-negative
/// errors. One line per kind of problem; empty when all is well.
std::vector<std::string> validate_hierarchy(const VertexHierarchy& h);

/// Encodes everything of `h` but the base mesh (BASE holds it).
/// \return kInvalidInput ("cannot encode VHIE: ...") when validate_hierarchy()
///         finds a problem; kRuntime when memory runs out. Deterministic.
Result<Bytes> encode_vhie(const VertexHierarchy& h);

/// Decodes a VHIE payload onto `base` (BASE's mesh: its vertex count must
/// equal the stored root count). Every count is checked against the bytes
/// that remain before anything is allocated; the result passes
/// validate_hierarchy().
/// \return LBK-E023 "section VHIE: ..." (kInvalidInput) for any deviation:
///         root count other than BASE's, unknown flags, a structure stream
///         that does not describe full binary trees filling node_count
///         nodes, a stored depth that is not the trees' own or above 64,
///         cut vertices out of range or both missing, a permutation that is
///         not one, non-finite values, nonzero padding, trailing bytes.
Result<VertexHierarchy> decode_vhie(const uint8_t* data, size_t size, TriangleMesh base);

/// The fixed fields, with the size checks that need no decoding.
Result<VhieSummary> read_vhie_summary(const uint8_t* data, size_t size);

}  // namespace lodbake
