// The compact codecs (codec 1) of the section kinds other than VSPL
// (docs/format.md "Codecs"): those that need no other section (VTRE, SETS,
// VHIE, RFIN, DAGE) and those coded against the container's BASE (FANH, STRP,
// WEDG).
// VSPL's compact codec, also against BASE, has its own entry points
// (formats/sections/vspl_compact.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// True when `tag` defines a compact codec that needs no other section.
bool has_standalone_compact_codec(std::string_view tag);

/// The compact bytes of the raw payload of a `tag` section.
/// \pre has_standalone_compact_codec(tag).
/// \return the kind's encoder's result: the payload's decoder error when it
///         is malformed (kInvalidInput), kUnsupported for a valid payload
///         the codec cannot reproduce (keep it raw).
Result<Bytes> encode_section_compact(std::string_view tag, const uint8_t* raw, size_t size);

/// The raw payload that the compact bytes `data` of a `tag` section encode.
/// \pre has_standalone_compact_codec(tag).
/// \return the kind's decoder's result (LBK-E023 for malformed bytes).
Result<Bytes> decode_section_compact(std::string_view tag, const uint8_t* data, size_t size);

/// True when `tag` defines a compact codec coded against BASE's triangles
/// (which recoding BASE never changes).
bool has_base_compact_codec(std::string_view tag);

/// As encode_section_compact(), against `base` (the decoded BASE mesh).
/// \pre has_base_compact_codec(tag).
Result<Bytes> encode_section_compact(std::string_view tag, const uint8_t* raw, size_t size,
                                     const TriangleMesh& base);

/// As decode_section_compact(), against `base`.
/// \pre has_base_compact_codec(tag).
Result<Bytes> decode_section_compact(std::string_view tag, const uint8_t* data, size_t size,
                                     const TriangleMesh& base);

}  // namespace lodbake
