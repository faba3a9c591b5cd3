// The SETS section: the Sorted Edge Triangle Strip graph of Belmonte,
// Aguado and Sancho (ICCS 2006), one labelled graph per triangle strip,
// from which the strips of any level of detail of a progressive mesh are
// recovered (lib/strips/sets_recovery.h). Built by lib/strips/sets_build.h.
// Byte layout: docs/format.md "SETS".
//
// LoD l is the mesh after the first l contractions of the progressive mesh
// (the reverse of its splits): LoD 0 is the full mesh, LoD lod_count - 1
// the base mesh. A label is the paper's "maximum LoD until it is valid":
// the entry valid at LoD l is the first one of its sorted list whose label
// is >= l.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "formats/sections/vspl.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The END successor (and an empty strip's beginning).
inline constexpr uint32_t kSetsEnd = std::numeric_limits<uint32_t>::max();

/// The graph in flat arrays. Node ids are global (strip s owns nodes
/// [node_first[s], node_first[s+1])) and successors name nodes of the same
/// strip or kSetsEnd.
struct SetsGraph {
  uint32_t vertex_count = 0;  ///< of the full mesh (PM vertex ids)
  uint32_t lod_count = 1;     ///< contractions + 1

  // Per strip.
  std::vector<uint32_t> beginning_first{0};  ///< strip s: beginnings [b[s], b[s+1])
  std::vector<uint32_t> node_first{0};       ///< strip s: nodes [n[s], n[s+1])
  // StripBeginning: first node of the strip (kSetsEnd: empty) and its label.
  std::vector<uint32_t> beginning_lod;
  std::vector<uint32_t> beginning_node;
  // ColElm: the vertex and the node's arcs [arc_first[n], arc_first[n+1]).
  std::vector<uint32_t> node_vertex;
  std::vector<uint32_t> arc_first{0};
  // RawElm: label and the successor run [successor_first[a], successor_first[a+1]):
  // the node after each occurrence of the vertex in the strip, in strip order.
  std::vector<uint32_t> arc_lod;
  std::vector<uint32_t> successor_first{0};
  std::vector<uint32_t> successors;

  size_t strip_count() const { return node_first.size() - 1; }
  size_t node_count() const { return node_vertex.size(); }
  size_t arc_count() const { return arc_lod.size(); }
  bool operator==(const SetsGraph& o) const {
    return vertex_count == o.vertex_count && lod_count == o.lod_count &&
           beginning_first == o.beginning_first && node_first == o.node_first &&
           beginning_lod == o.beginning_lod && beginning_node == o.beginning_node &&
           node_vertex == o.node_vertex && arc_first == o.arc_first && arc_lod == o.arc_lod &&
           successor_first == o.successor_first && successors == o.successors;
  }
};

/// The fixed fields of a SETS payload.
struct SetsSummary {
  uint32_t vertex_count = 0;
  uint32_t lod_count = 0;
  uint32_t strip_count = 0;
  uint32_t beginning_count = 0;
  uint32_t node_count = 0;
  uint32_t arc_count = 0;
  uint32_t successor_count = 0;
  // Widths of the per-strip, per-node and per-arc counts (stored minus 1).
  uint8_t beginnings_bits = 0;
  uint8_t nodes_bits = 0;
  uint8_t arcs_bits = 0;
  uint8_t successors_bits = 0;
};

inline constexpr size_t kSetsFixedBytes = 32;

/// The structural rules every decoded graph satisfies (and encode_sets()
/// requires): arrays of consistent sizes; every strip has at least one node
/// and one beginning, every node one arc, every arc one successor; vertices
/// < vertex_count; beginnings and successors name a node of their own strip
/// or kSetsEnd; labels strictly increasing within each list and < lod_count,
/// the last one of each list == lod_count - 1. The first violation, or ok.
Status check_sets_structure(const SetsGraph& graph);

/// Encodes `graph`. Deterministic.
/// \return kInvalidInput ("cannot encode SETS: ...") when
///         check_sets_structure() fails or a count exceeds 2^32 - 1.
Result<Bytes> encode_sets(const SetsGraph& graph);

/// Decodes a SETS payload: counts are checked against the payload size
/// before anything is allocated (every successor and beginning costs at least
/// one bit, and each strip, node and arc owns at least one of the next
/// level), then check_sets_structure() runs on the result.
/// \return the graph, or LBK-E023 "section SETS: ..." (kInvalidInput).
Result<SetsGraph> decode_sets(const uint8_t* data, size_t size, SetsSummary* summary = nullptr);

/// The fixed fields, checked against each other and the payload size: O(1).
Result<SetsSummary> read_sets_summary(const uint8_t* data, size_t size);

/// The LoDs at which strip s's sequence may change: 0 and every label + 1
/// of its beginnings and its nodes' arcs below lod_count, sorted, unique.
/// Two consecutive entries bound a validity interval (the paper's
/// coherence array).
std::vector<uint32_t> strip_change_lods(const SetsGraph& graph, size_t strip);

/// Recovers strip s at `lod` with a plain walk of the graph (the reference
/// for lib/strips' fast walk, and what validation runs).
/// \return the sequence, or kInvalidInput naming the problem when the walk
///         uses a successor run past its end, never reaches END within the
///         strip's successor total, or `lod` is out of range.
Result<std::vector<uint32_t>> walk_strip(const SetsGraph& graph, size_t strip, uint32_t lod);

/// Deep check for `lodbake-inspect --validate`: the structure, then every
/// strip walked at every LoD where it may change: each walk reaches END
/// without running past a successor run, and a strip is never longer than
/// at LoD 0 (recovery sizes its buffers from LoD 0). One line per kind of
/// problem with its count and first instance; empty when all is well.
std::vector<std::string> validate_sets(const SetsGraph& graph);

/// decode_sets() then validate_sets(), and the graph against the progressive
/// mesh (VSPL) it was built over: vertex_count == its full vertex count and
/// lod_count == splits + 1. A decode error is the single finding; without a
/// VSPL section, that is a finding; with an unreadable one (`vspl` null)
/// the graph is checked alone.
std::vector<std::string> validate_sets_payload(const uint8_t* data, size_t size, bool has_vspl,
                                               const VsplSummary* vspl);

}  // namespace lodbake
