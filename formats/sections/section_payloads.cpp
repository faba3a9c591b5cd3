// Which codec each section kind defines (docs/format.md "Codecs"): BASE
// raw or draco, VSPL, FANH and STRP raw or compact (against BASE), the kinds of
// compact_sections.h raw or compact (alone), every other kind raw only. A pack tool
// that does not know a kind copies its bytes as they are, so a kind gains
// codecs here without older tools mangling it.
#include "formats/sections/section_payloads.h"

#include <cinttypes>
#include <new>
#include <optional>

#include "formats/container/container_errors.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/draco_codec.h"
#include "formats/sections/vspl_compact.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status undefined_codec(const Section& section) {
  const char* name = codec_name(section.entry.codec);
  return container_error(
      ContainerError::kUnknownCodec,
      string_printf("section %s uses codec %u (%s), which is not defined for this section kind",
                    section.tag().c_str(), section.entry.codec, name == nullptr ? "?" : name));
}

// " of group N" for sections outside group 0, so messages about 1.0 files
// read as before.
std::string in_group(const Section& section) {
  return section.group() == 0 ? std::string() : " of group " + std::to_string(section.group());
}

}  // namespace

Result<Bytes> decode_base_stored(const Section& section) {
  if (section.entry.codec == static_cast<uint16_t>(SectionCodec::kRaw))
    return Bytes(section.data, section.data + section.size);
  if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kDraco))
    return undefined_codec(section);
  if (codec_available(section.entry.codec)) {
    LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base_draco(section.data, section.size));
    Result<Bytes> raw = encode_base(mesh, BaseEncodeOptions{});
    if (!raw.is_ok() && raw.status().kind() == ErrorKind::kInvalidInput)
      return malformed_section(kBaseTag, "draco: " + raw.status().message());
    return raw;
  }
  return container_error(ContainerError::kUnknownCodec,
                         "section BASE uses codec 2 (draco), which this build cannot decode");
}

Result<Bytes> decode_vspl_stored(const Section& section, const TriangleMesh& base) {
  if (section.entry.codec == static_cast<uint16_t>(SectionCodec::kRaw))
    return Bytes(section.data, section.data + section.size);
  if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kCompact))
    return undefined_codec(section);
  return decode_vspl_compact(section.data, section.size, base);
}

Result<Bytes> decode_with_base_stored(const Section& section, const TriangleMesh& base) {
  if (section.entry.codec == static_cast<uint16_t>(SectionCodec::kRaw))
    return Bytes(section.data, section.data + section.size);
  if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kCompact) ||
      !has_base_compact_codec(section.tag()))
    return undefined_codec(section);
  return decode_section_compact(section.tag(), section.data, section.size, base);
}

Result<Bytes> decode_stored_payload(const Section& section) {
  if (section.entry.codec == static_cast<uint16_t>(SectionCodec::kRaw))
    return Bytes(section.data, section.data + section.size);
  if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kCompact) ||
      !has_standalone_compact_codec(section.tag()))
    return undefined_codec(section);
  return decode_section_compact(section.tag(), section.data, section.size);
}

Status decode_section_codecs(Container* container, std::vector<Bytes>* storage) {
  try {
    storage->reserve(storage->size() + container->sections.size());
    auto replace = [&](Section* section, Bytes raw) -> Status {
      if (raw.size() != section->entry.decoded_size) {
        return container_error(
            ContainerError::kSizeMismatch,
            string_printf("section %s decodes to %zu bytes, its entry says %" PRIu64,
                          section->tag().c_str(), raw.size(), section->entry.decoded_size));
      }
      storage->push_back(std::move(raw));
      section->data = storage->back().data();
      section->size = storage->back().size();
      return Status::ok();
    };
    // Each group's BASE first: the compact codecs of its other sections
    // predict from it.
    std::vector<Section*> bases(container->group_count(), nullptr);
    for (Section& section : container->sections) {
      if (section.tag() == kBaseTag) bases[section.group()] = &section;
    }
    for (Section* base : bases) {
      if (base == nullptr || base->entry.codec == static_cast<uint16_t>(SectionCodec::kRaw))
        continue;
      LODBAKE_ASSIGN_OR_RETURN(Bytes raw, decode_base_stored(*base));
      LODBAKE_RETURN_IF_ERROR(replace(base, std::move(raw)));
    }
    std::vector<std::optional<TriangleMesh>> base_meshes(bases.size());
    for (Section& section : container->sections) {
      // Kinds this build does not know keep their stored bytes: their own
      // tools define their codecs.
      if (section.entry.codec == static_cast<uint16_t>(SectionCodec::kRaw) ||
          section.tag() == kBaseTag || !section.known)
        continue;
      if (has_standalone_compact_codec(section.tag())) {
        LODBAKE_ASSIGN_OR_RETURN(Bytes raw, decode_stored_payload(section));
        LODBAKE_RETURN_IF_ERROR(replace(&section, std::move(raw)));
        continue;
      }
      const bool vspl = section.tag() == kVsplTag;
      if ((!vspl && !has_base_compact_codec(section.tag())) ||
          section.entry.codec != static_cast<uint16_t>(SectionCodec::kCompact))
        return undefined_codec(section);
      const Section* base = bases[section.group()];
      if (base == nullptr) {
        return container_error(ContainerError::kMissingSection,
                               "section " + section.tag() + in_group(section) +
                                   " is compact, which needs the BASE section" + in_group(section));
      }
      std::optional<TriangleMesh>& base_mesh = base_meshes[section.group()];
      if (!base_mesh) {
        LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base(base->data, base->size));
        base_mesh = std::move(mesh);
      }
      LODBAKE_ASSIGN_OR_RETURN(Bytes raw, vspl ? decode_vspl_stored(section, *base_mesh)
                                               : decode_with_base_stored(section, *base_mesh));
      LODBAKE_RETURN_IF_ERROR(replace(&section, std::move(raw)));
    }
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding section codecs");
  }
}

}  // namespace lodbake
