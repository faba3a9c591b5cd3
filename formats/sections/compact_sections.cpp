// Two tables from tag to codec (alone, against BASE), so that the
// container decoder (section_payloads.cpp), lodbake-pack and the benchmark
// learn a new kind's compact codec from one line.
#include "formats/sections/compact_sections.h"

#include "formats/container/section_registry.h"
#include "formats/sections/dage_compact.h"
#include "formats/sections/fanh_compact.h"
#include "formats/sections/rfin_compact.h"
#include "formats/sections/sets_compact.h"
#include "formats/sections/strp_compact.h"
#include "formats/sections/vhie_compact.h"
#include "formats/sections/vtre_compact.h"
#include "formats/sections/wedg_compact.h"

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
    {kDageTag, encode_dage_compact, decode_dage_compact},
};

struct BaseCompactCodec {
  const char* tag;
  Result<Bytes> (*encode)(const uint8_t*, size_t, const TriangleMesh&);
  Result<Bytes> (*decode)(const uint8_t*, size_t, const TriangleMesh&);
};

const BaseCompactCodec kBaseCodecs[] = {
    {kFanhTag, encode_fanh_compact, decode_fanh_compact},
    {kStrpTag, encode_strp_compact, decode_strp_compact},
    {kWedgTag, encode_wedg_compact, decode_wedg_compact},
};

const BaseCompactCodec* find_base(std::string_view tag) {
  for (const BaseCompactCodec& codec : kBaseCodecs) {
    if (tag == codec.tag) return &codec;
  }
  return nullptr;
}

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

bool has_base_compact_codec(std::string_view tag) {
  return find_base(tag) != nullptr;
}

Result<Bytes> encode_section_compact(std::string_view tag, const uint8_t* raw, size_t size,
                                     const TriangleMesh& base) {
  const BaseCompactCodec* codec = find_base(tag);
  if (codec == nullptr) return Status(ErrorKind::kUnsupported, "no compact codec for this kind");
  return codec->encode(raw, size, base);
}

Result<Bytes> decode_section_compact(std::string_view tag, const uint8_t* data, size_t size,
                                     const TriangleMesh& base) {
  const BaseCompactCodec* codec = find_base(tag);
  if (codec == nullptr) return Status(ErrorKind::kUnsupported, "no compact codec for this kind");
  return codec->decode(data, size, base);
}

}  // namespace lodbake
