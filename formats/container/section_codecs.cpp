// A fixed table like the section registry: what a build accepts is visible
// in one place. The test switch is a plain flag set, read by the reader's
// codec check (container_reader.cpp), so disabling a codec makes every
// reader fail exactly as a build without it would (LBK-E020, exit code 5).
#include "formats/container/section_codecs.h"

namespace lodbake {
namespace {

bool disabled[3] = {false, false, false};

}  // namespace

const char* codec_name(uint16_t codec) {
  switch (codec) {
    case static_cast<uint16_t>(SectionCodec::kRaw):
      return "raw";
    case static_cast<uint16_t>(SectionCodec::kCompact):
      return "compact";
    case static_cast<uint16_t>(SectionCodec::kDraco):
      return "draco";
    default:
      return nullptr;
  }
}

bool draco_codec_built() {
#ifdef LODBAKE_HAVE_DRACO_CODEC
  return true;
#else
  return false;
#endif
}

bool codec_available(uint16_t codec) {
  if (codec == static_cast<uint16_t>(SectionCodec::kRaw)) return true;
  if (codec == static_cast<uint16_t>(SectionCodec::kCompact)) return !disabled[codec];
  if (codec == static_cast<uint16_t>(SectionCodec::kDraco))
    return draco_codec_built() && !disabled[codec];
  return false;
}

void set_codec_disabled_for_testing(SectionCodec codec, bool is_disabled) {
  const uint16_t c = static_cast<uint16_t>(codec);
  if (c == static_cast<uint16_t>(SectionCodec::kRaw) || c >= 3) return;
  disabled[c] = is_disabled;
}

}  // namespace lodbake
