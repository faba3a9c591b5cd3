// Internal to lib/dracoio: a check of a Draco stream's fixed 11-byte header
// before draco::Decoder sees the stream.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/status.h"

namespace lodbake {
namespace dracoio {

// Accepts only triangle meshes in mesh bitstream version 2.2 (what Draco
// 1.3 and later write) with the sequential or edgebreaker method. Older
// bitstream versions are refused (kUnsupported): Draco 1.5.5's legacy
// decoding paths take 32-bit counts from the stream unchecked, so a 34-byte
// file can make it allocate and fill tens of gigabytes. Point clouds are
// refused with a message saying so.
Status check_draco_header(const uint8_t* data, size_t size);

}  // namespace dracoio
}  // namespace lodbake
