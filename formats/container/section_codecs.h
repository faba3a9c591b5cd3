// The section codecs a container may name (docs/format.md "Codecs") and
// which of them this build can decode. Draco support is a build option
// (LODBAKE_DRACO_CODEC); tests can also switch a codec off at run time to
// exercise the "unsupported codec" path of a reader without Draco.
#pragma once

#include <cstdint>

#include "formats/container/container_layout.h"

namespace lodbake {

/// "raw", "compact", "draco", or nullptr for a value the format does not define.
const char* codec_name(uint16_t codec);

/// True when this build can decode sections stored with `codec`: raw and
/// compact always, draco when built with Draco support and not switched off.
bool codec_available(uint16_t codec);

/// True when this build was compiled with the Draco codec.
bool draco_codec_built();

/// Test hook: makes codec_available(codec) false (or restores it) for the
/// whole process, as if the build lacked it. Not thread-safe; raw cannot be
/// switched off.
void set_codec_disabled_for_testing(SectionCodec codec, bool disabled);

}  // namespace lodbake
