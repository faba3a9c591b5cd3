// The RFIN section: per-split refinement data of the hierarchy in VHIE for
// Hoppe's view-dependent criteria (bounding sphere, cone of normals,
// screen-space error terms mu^2 and delta^2), one record per internal node
// in VHIE's array order. Byte layout: docs/format.md "RFIN".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

inline constexpr size_t kRfinFixedBytes = 8;
/// Bytes per record: radius, mu^2, delta^2 as float32, then 48 bits of
/// octahedral axis (2 x 16) and half-angle (16).
inline constexpr size_t kRfinRecordBytes = 18;

/// One RFIN record as stored: radius, mu^2, delta^2 as float32, the cone axis
/// octahedral-mapped to 2 x 16 bits and the half-angle in units of
/// pi / 65535. View-dependent streaming (lib/replay/stream_packets.h) sends
/// these bits unchanged, so a client decodes exactly the values its server
/// evaluates qrefine() on.
struct RfinRecord {
  float radius = 0;
  float mu2 = 0;
  float delta2 = 0;
  uint16_t axis_x = 0;
  uint16_t axis_y = 0;
  uint16_t half_angle = 0;
};

/// Quantizes one node's data as encode_rfin() stores it (the stored cone
/// contains the given one). \return kInvalidInput when a value is negative
/// or not finite.
Result<RfinRecord> quantize_refinement(const NodeRefinement& data);

/// The values a record stands for, as decode_rfin() gives them. A record
/// whose floats are negative or not finite is the caller's to refuse
/// (rfin_record_is_valid()).
NodeRefinement dequantize_refinement(const RfinRecord& record);

/// radius, mu^2 and delta^2 finite and non-negative.
bool rfin_record_is_valid(const RfinRecord& record);

/// Encodes the records of the internal nodes of `h` (`data` has one entry per
/// node; leaves' entries are ignored). The axis is quantized and the stored
/// half-angle rounded up so that the stored cone contains the given one.
/// \return kInvalidInput ("cannot encode RFIN: ...") when sizes differ or a
///         value is negative or not finite.
Result<Bytes> encode_rfin(const VertexHierarchy& h, const std::vector<NodeRefinement>& data);

/// Decodes an RFIN payload for `h` (from VHIE): one entry per node, leaves
/// all zero. \return LBK-E023 "section RFIN: ..." when the split count is
/// not VHIE's, the size is not exact, flags are unknown, a value is negative
/// or not finite (16-bit half-angles cannot exceed pi).
Result<std::vector<NodeRefinement>> decode_rfin(const uint8_t* data, size_t size,
                                                const VertexHierarchy& h);

/// decode_rfin()'s records before dequantization (one per node, leaves all
/// zero), with the same checks.
Result<std::vector<RfinRecord>> decode_rfin_records(const uint8_t* data, size_t size,
                                                    const VertexHierarchy& h);

/// The stored split count, after checking the exact size: O(1).
Result<uint32_t> read_rfin_summary(const uint8_t* data, size_t size);

}  // namespace lodbake
