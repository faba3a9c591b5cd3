// The VSPL section: the vertex-split records of a progressive mesh (Hoppe
// 1996) and the permutation from PM vertex ids to input vertex ids. A
// container holding a progressive mesh has BASE (the coarsest mesh) + VSPL
// (+ META). Byte layout: docs/format.md "VSPL".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/quantization.h"
#include "formats/support/status.h"

namespace lodbake {

/// Flag bit 0: every record stores vs's position after the split. When
/// clear, that position is vs's position before the split (half-edge
/// placement: no vertex ever moves), so it is not stored.
inline constexpr uint8_t kVsplStoresVsPositions = 0x01;
/// Flag bit 1: the input permutation is stored. When clear it is the
/// identity (PM vertex v is input vertex v).
inline constexpr uint8_t kVsplStoresPermutation = 0x02;
/// Flag bit 2: the progressive mesh carries per-vertex normals; the normal
/// of each split's new vertex is stored (BASE holds the base vertices').
inline constexpr uint8_t kVsplStoresNormals = 0x04;
/// Flag bit 3: the same for texture coordinates.
inline constexpr uint8_t kVsplStoresTexcoords = 0x08;
/// Every flag bit defined in format 1.0.
inline constexpr uint8_t kVsplKnownFlags =
    kVsplStoresVsPositions | kVsplStoresPermutation | kVsplStoresNormals | kVsplStoresTexcoords;

/// The bytes before the quantization box and the records.
inline constexpr size_t kVsplFixedBytes = 19;
/// Where the fixed fields' error range (min, max: two float32) starts.
inline constexpr size_t kVsplErrorRangeOffset = 11;

struct VsplEncodeOptions {
  bool quantize = false;  ///< false: float32 positions (exact round trip)
  int bits = 16;          ///< bits per coordinate when quantizing, 1..30
};

/// The fixed fields of a VSPL payload: what inspect shows without decoding
/// the records.
struct VsplSummary {
  uint32_t split_count = 0;        ///< R, the number of vertex-split records
  uint32_t base_vertex_count = 0;  ///< B, must equal BASE's vertex count
  PositionEncoding position_encoding = PositionEncoding::kFloat32;
  uint8_t quantization_bits = 0;  ///< 0 for float32
  uint8_t flags = 0;              ///< kVsplStores* bits (kVsplKnownFlags)
  float min_error = 0;            ///< the smallest record error (0 when R == 0)
  float max_error = 0;            ///< the largest record error (0 when R == 0)
  Vec3f box_min{};                ///< dequantization box (quantized only)
  Vec3f box_max{};

  /// B + R: the vertex count of the fully refined mesh.
  uint64_t full_vertex_count() const { return uint64_t{base_vertex_count} + split_count; }
};

/// A decoded VSPL payload: everything of a ProgressiveMesh but the base mesh
/// (and the base vertices' attributes, which BASE holds).
struct VsplSection {
  VsplSummary summary;
  std::vector<VertexSplit> splits;     ///< vs_position always filled (stored or implied)
  std::vector<uint32_t> input_vertex;  ///< always full_vertex_count() entries
  /// Flag bit 2: 3 floats per split, the normal of the vertex it creates
  /// (PM vertex B + i), in split order; empty otherwise.
  std::vector<float> split_normals;
  /// Flag bit 3: 2 floats per split, likewise; empty otherwise.
  std::vector<float> split_texcoords;
};

/// Encodes the records, the permutation and the split vertices' attributes
/// of `pm` as a VSPL payload (pm.base goes to BASE, base vertices'
/// attributes included). Deterministic. The writer stores vs positions
/// only when some split's vs_position differs (bitwise) from vs's position
/// before the split, the permutation only when it is not the identity, and
/// normals / texture coordinates exactly when pm carries them (float32,
/// never quantized). With quantize, the box is the bounding box of the
/// stored positions and coordinates are quantized as
/// formats/support/quantization.h specifies.
/// \return kInvalidInput ("cannot encode VSPL: ...") when the PM is not
///         storable (see validate_vspl(), the first problem), or bits
///         outside 1..30 when quantizing; kRuntime when memory runs out.
Result<Bytes> encode_vspl(const ProgressiveMesh& pm, const VsplEncodeOptions& options);

/// Decodes a VSPL payload against its base mesh's positions (from BASE):
/// the stored base vertex count must equal base_positions.size(), and
/// unstored vs positions are taken from the base positions and earlier
/// records. Every count is checked against the bytes that remain before
/// anything is allocated; memory stays proportional to `size` plus
/// base_positions.size().
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the records and the permutation, and the fixed fields in
///         `*summary` when not null; or LBK-E023 "section VSPL: ..."
///         (kInvalidInput) for any deviation from the layout: unknown
///         encoding or flag bits, bits out of range, a base vertex count
///         other than base_positions.size(), more than 2^32 - 1 vertices,
///         splits over fewer than 2 base vertices, a non-finite or inverted
///         box, counts needing more bytes than remain, vs / vl / vr out of
///         range or equal, a split with neither wing, a non-finite float
///         (position, error, normal or texture coordinate), an error range
///         that is not the records' own, a permutation that is not one,
///         nonzero padding bits, trailing bytes. Never throws.
Result<VsplSection> decode_vspl(const uint8_t* data, size_t size,
                                const std::vector<Vec3f>& base_positions,
                                VsplSummary* summary = nullptr);

/// Reads only the fixed fields and checks that the payload has exactly the
/// size they imply: O(1) time and memory. Checks the same layout constraints
/// as decode_vspl() except what needs the base mesh or the record contents.
Result<VsplSummary> read_vspl_summary(const uint8_t* data, size_t size);

/// Where the parts of a VSPL payload lie (byte offsets into the payload),
/// for codecs that transcode it (formats/sections/vspl_compact.h).
struct VsplParts {
  VsplSummary summary;
  size_t topology_offset = 0;  ///< also the size of the fixed fields and the box
  size_t topology_bytes = 0;
  size_t positions_offset = 0;
  size_t positions_bytes = 0;
  size_t errors_offset = 0;
  size_t tail_offset = 0;  ///< normals, texture coordinates, permutation: to the end
};

/// The parts of a payload whose size checks out (as read_vspl_summary()).
Result<VsplParts> locate_vspl_parts(const uint8_t* data, size_t size);

/// The payload with every record's error and the header's error range
/// rounded up to `significant_bits` (round_up_to_significant_bits()): the
/// lossy step behind `lodbake-pack --error-bits`, after which the compact
/// codec stores each error in fewer bits (layout version 4). Everything else
/// is unchanged, byte for byte; rounding a rounded payload changes nothing.
/// \return locate_vspl_parts()'s error for a payload whose parts do not add
///         up; kInvalidInput for significant_bits outside 1..24.
Result<Bytes> round_vspl_errors(const uint8_t* data, size_t size, int significant_bits);

/// Joins a decoded BASE mesh and a VSPL section decoded against its
/// positions into a progressive mesh. ProgressiveMesh::normals (texcoords)
/// is BASE's per-vertex values followed by the section's split values.
/// \return LBK-E023 "section VSPL: ..." (kInvalidInput) when the two do not
///         belong together: base vertex counts differ, VSPL stores an
///         attribute that BASE lacks or holds per corner (a progressive mesh
///         needs it per vertex), or BASE has an attribute that VSPL does not
///         store for the split vertices.
Result<ProgressiveMesh> join_progressive_mesh(TriangleMesh base, VsplSection section);

/// The progressive mesh stored in a BASE and a VSPL payload, attributes
/// included.
/// \return decode_base()'s, decode_vspl()'s or join_progressive_mesh()'s
///         error.
Result<ProgressiveMesh> decode_progressive_mesh(const uint8_t* base_data, size_t base_size,
                                                const uint8_t* vspl_data, size_t vspl_size);

/// Deep check of a progressive mesh's records as VSPL stores them (for
/// `lodbake-inspect --validate`): more than 2^32 - 1 vertices, splits over
/// fewer than 2 base vertices, vs / vl / vr out of range for the vertex count
/// at their split or repeating a vertex, splits with neither wing,
/// non-finite positions or errors, input_vertex of the wrong size or not a
/// permutation, normals / texture coordinates that are not per-vertex with
/// 3 / 2 components for all full_vertex_count() vertices, hold a non-finite
/// value, or disagree (bitwise, or in presence) with pm.base's. Each kind of
/// problem gives one line with its count and first instance; empty when all
/// is well.
/// Whether the splits fit the base mesh's connectivity is the replay's check
/// (lib/simplify), not the format's.
std::vector<std::string> validate_vspl(const ProgressiveMesh& pm);

/// decode_vspl() then validate_vspl(): a decode error is the single finding.
std::vector<std::string> validate_vspl_payload(const uint8_t* data, size_t size,
                                               const std::vector<Vec3f>& base_positions);

/// Triangles of the fully refined mesh: `base_triangles` plus 2 per split
/// (1 for a boundary split, vl or vr == kNoVertex).
uint64_t full_triangle_count(uint64_t base_triangles, const std::vector<VertexSplit>& splits);

}  // namespace lodbake
