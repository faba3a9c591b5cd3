// One table from tag to codec, so that the container decoder
// (section_payloads.cpp) and lodbake-pack learn a new kind's compact codec
// from one line.
#include "formats/sections/compact_sections.h"

#include "formats/container/section_registry.h"
#include "formats/sections/rfin_compact.h"
#include "formats/sections/sets_compact.h"
#include "formats/sections/vhie_compact.h"
#include "formats/sections/vtre_compact.h"

namespace lodbake {
namespace {

struct CompactCodec {
  const char* tag;
  Result<Bytes> (*encode)(const uint8_t*, size_t);
  Result<Bytes> (*decode)(const uint8_t*, size_t);
};

const CompactCodec kCodecs[] = {
    {kVtreTag, encode_vtre_compact, decode_vtre_compact},
    {kSetsTag, encode_sets_compact, decode_sets_compact},
    {kVhieTag, encode_vhie_compact, decode_vhie_compact},
    {kRfinTag, encode_rfin_compact, decode_rfin_compact},
};

const CompactCodec* find(std::string_view tag) {
  for (const CompactCodec& codec : kCodecs) {
    if (tag == codec.tag) return &codec;
  }
  return nullptr;
}

}  // namespace

bool has_standalone_compact_codec(std::string_view tag) {
  return find(tag) != nullptr;
}

Result<Bytes> encode_section_compact(std::string_view tag, const uint8_t* raw, size_t size) {
  const CompactCodec* codec = find(tag);
  if (codec == nullptr) return Status(ErrorKind::kUnsupported, "no compact codec for this kind");
  return codec->encode(raw, size);
}

Result<Bytes> decode_section_compact(std::string_view tag, const uint8_t* data, size_t size) {
  const CompactCodec* codec = find(tag);
  if (codec == nullptr) return Status(ErrorKind::kUnsupported, "no compact codec for this kind");
  return codec->decode(data, size);
}

}  // namespace lodbake
