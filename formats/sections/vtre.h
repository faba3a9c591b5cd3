// The VTRE section: To-Lau-Green vertex trees of a progressive mesh, as the
// paper's three kinds of node records (base, left, right) with their vertex
// fans, bit-packed. Byte layout: docs/format.md "VTRE".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/vertex_trees.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The bytes before the positions.
inline constexpr size_t kVtreFixedBytes = 20;

/// The fixed fields of a VTRE payload.
struct VtreSummary {
  uint32_t base_vertex_count = 0;  ///< B: base nodes
  uint32_t split_count = 0;        ///< S: S left and S right nodes
  uint32_t run_count = 0;          ///< fan runs over all nodes
  uint32_t fan_vertex_count = 0;   ///< fan entries over all runs
  uint8_t id_bits = 0;             ///< bits per vertex id: bits_for_count(B + S)
  uint8_t run_count_bits = 0;      ///< bits per node's run count
  uint8_t run_length_bits = 0;     ///< bits per run length

  uint64_t node_count() const { return uint64_t{base_vertex_count} + 2 * uint64_t{split_count}; }
};

/// Stored size of each kind of node record, in bits: a record is its fields
/// in the bit stream (base: state, fan; left: parent id, state, fan; right:
/// fan) plus, for base and left records, the 12 bytes of the coordinate.
struct VtreRecordSizes {
  uint64_t base_records = 0, base_bits = 0;
  uint64_t left_records = 0, left_bits = 0;
  uint64_t right_records = 0, right_bits = 0;
};

/// Encodes `trees` as a VTRE payload (positions float32). Deterministic.
/// \return kInvalidInput ("cannot encode VTRE: ...") when the trees are
///         malformed (see validate_vtre()); kRuntime when memory runs out.
Result<Bytes> encode_vtre(const VertexTrees& trees);

/// Decodes a VTRE payload. Every count is checked against the bytes that
/// remain before anything is allocated.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the trees (and the fixed fields in `*summary`, the record sizes
///         in `*sizes`, when not null) or LBK-E023 "section VTRE: ..." for
///         any deviation: nonzero reserved byte, bit widths out of range,
///         counts the payload cannot hold, a non-finite coordinate, a parent
///         vertex that does not exist at its split, a fan vertex that does
///         not exist at its node or is the node's own vertex, an open run of
///         fewer than 2 or a closed run of fewer than 3 vertices, run or fan
///         totals other than the header's, nonzero padding, trailing bytes.
///         Never throws.
Result<VertexTrees> decode_vtre(const uint8_t* data, size_t size, VtreSummary* summary = nullptr,
                                VtreRecordSizes* sizes = nullptr);

/// Reads only the fixed fields and checks what they alone imply: O(1).
Result<VtreSummary> read_vtre_summary(const uint8_t* data, size_t size);

/// The record sizes `trees` would be stored with.
VtreRecordSizes vtre_record_sizes(const VertexTrees& trees);

/// Structural findings on in-memory trees (what decode_vtre() enforces on
/// bytes, plus array shapes): empty when they can be stored.
std::vector<std::string> validate_vtre(const VertexTrees& trees);

}  // namespace lodbake
