// The FANH section: a fan-hierarchy (Livny, Sokolovsky & El-Sana 2007) over
// the mesh in BASE (the input, fully refined): per internal node its
// children (the fine path's order), error, and the triangles each child's
// collapse removes and modifies. Byte layout: docs/format.md "FANH".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The bytes before the errors and the bit stream.
inline constexpr size_t kFanhFixedBytes = 32;

/// The fixed fields of a FANH payload.
struct FanhSummary {
  uint32_t vertex_count = 0;      ///< leaves; must equal BASE's vertex count
  uint32_t triangle_count = 0;    ///< must equal BASE's triangle count
  uint32_t internal_count = 0;    ///< fan-merges
  uint32_t child_entries = 0;     ///< children of all internal nodes, centres included
  uint32_t removed_entries = 0;   ///< length of all removed lists together
  uint32_t modified_entries = 0;  ///< length of all modified lists together
};

/// Figures of a well-formed hierarchy (validate_fanh_structure() empty).
struct FanhStats {
  uint64_t internal_nodes = 0;
  uint64_t leaves = 0;
  uint64_t roots = 0;           ///< nodes without a parent: the coarsest mesh's vertices
  uint64_t depth = 0;           ///< edges on the longest root-to-leaf path; 0 without merges
  double average_children = 0;  ///< collapsed children per internal node (centres not counted)
  uint64_t removed_entries = 0;
  uint64_t modified_entries = 0;
};

/// Encodes a hierarchy. Deterministic.
/// \return kInvalidInput ("cannot encode FANH: ...") with the first finding
///         of validate_fanh_structure(); kRuntime when memory runs out.
Result<Bytes> encode_fanh(const FanHierarchy& hierarchy);

/// Decodes a FANH payload. Every count is checked against the bytes that
/// remain before anything is allocated.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the hierarchy, its fixed fields in *summary when not null; or
///         LBK-E023 "section FANH: ..." (kInvalidInput) for any deviation
///         from the layout: nonzero flags or reserved bytes, bit widths other
///         than the counts imply, a size other than the counts imply, a node
///         with fewer than 2 children, sums that disagree with the totals, a
///         non-finite or negative error, nonzero padding bits, and every
///         finding of validate_fanh_structure(). Never throws.
Result<FanHierarchy> decode_fanh(const uint8_t* data, size_t size, FanhSummary* summary = nullptr);

/// Reads the fixed fields and checks the payload size they imply: O(1).
Result<FanhSummary> read_fanh_summary(const uint8_t* data, size_t size);

/// The forest and list checks that need no mesh: offsets consistent,
/// at least 2 children per node, every child id below its parent's id
/// (children are made first), no node a child twice, empty lists for centre
/// entries, triangle ids below triangle_count, no triangle removed twice,
/// finite non-negative errors, fewer than 2^32 nodes. One line per kind of
/// problem with its count and first instance; empty when all is well.
std::vector<std::string> validate_fanh_structure(const FanHierarchy& hierarchy);

/// validate_fanh_structure(), then the counts against `base`, then a replay
/// of every fan-merge over `base` in construction order checking each list:
/// a child's removed triangles are alive and hold both the child's and the
/// centre's vertex, its modified ones are alive and hold the child's vertex
/// but not the centre's, and together they are all of the child's
/// triangles. Stops at the first node whose lists do not fit.
std::vector<std::string> validate_fanh(const FanHierarchy& hierarchy, const TriangleMesh& base);

/// decode_fanh() then validate_fanh(): a decode error is the single finding.
std::vector<std::string> validate_fanh_payload(const uint8_t* data, size_t size,
                                               const TriangleMesh& base);

/// \pre validate_fanh_structure(hierarchy) is empty.
FanhStats fanh_stats(const FanHierarchy& hierarchy);

}  // namespace lodbake
