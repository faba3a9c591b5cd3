// The compact codecs (codec 1) of the section kinds whose coding needs no
// other section (docs/format.md "Codecs"): VTRE, and the kinds added next
// to it. VSPL's compact codec needs BASE and has its own entry points
// (formats/sections/vspl_compact.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

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

}  // namespace lodbake
