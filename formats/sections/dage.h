// The DAGE section: the DAG of vertex splits of a progressive mesh (Zheng &
// Chan 2006), node i being the container's VSPL record i, each node's
// parents bit-packed in CSR form. Byte layout: docs/format.md "DAGE".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/vsplit_dag.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The bytes before the bit stream.
inline constexpr size_t kDageFixedBytes = 24;

/// The fixed fields of a DAGE payload.
struct DageSummary {
  uint32_t node_count = 0;         ///< N, one per vertex split
  uint32_t base_vertex_count = 0;  ///< B of the PM the DAG belongs to
  uint32_t edge_count = 0;         ///< E, parent links
  uint32_t root_count = 0;         ///< nodes without parents: Fs of the base mesh
  uint32_t leaf_count = 0;         ///< nodes without children: Fc of the full mesh
  uint8_t degree_bits = 0;         ///< bits per parent count (1..32; 0 when N == 0)
  uint8_t parent_bits = 0;         ///< bits per parent index: bits_for_count(N)
};

/// Encodes `dag` as a DAGE payload. Deterministic.
/// \return kInvalidInput ("cannot encode DAGE: ...") when the DAG is
///         malformed (offsets that do not span the parents, a parent not
///         below its node, parents not strictly increasing); kRuntime when
///         memory runs out.
Result<Bytes> encode_dage(const VsplitDag& dag);

/// Decodes a DAGE payload. Every count is checked against the bytes that
/// remain before anything is allocated.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the DAG, and the fixed fields in `*summary` when not null; or
///         LBK-E023 "section DAGE: ..." for any deviation from the layout:
///         nonzero reserved bytes, bit widths out of range, a payload size
///         other than the fields imply, degrees that do not sum to E, a
///         parent not below its node or not strictly increasing (so the graph
///         is acyclic), root or leaf counts other than the graph's, nonzero
///         padding. Never throws.
Result<VsplitDag> decode_dage(const uint8_t* data, size_t size, DageSummary* summary = nullptr);

/// Reads only the fixed fields and checks that the payload has exactly the
/// size they imply: O(1).
Result<DageSummary> read_dage_summary(const uint8_t* data, size_t size);

/// Deep checks (for `lodbake-inspect --validate`) of a decoded DAG: no edge
/// is transitively implied by the others, and the two fronts' counters stay
/// consistent through a full refinement in node order and a full coarsening
/// back (every node legal when reached, every counter back to its initial
/// value). One line per kind of problem; empty when all is well.
std::vector<std::string> validate_dage(const VsplitDag& dag);

}  // namespace lodbake
