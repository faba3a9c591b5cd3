// Strict container reader (docs/format.md "Reading"). The order of the
// checks is part of the specification: each value is checked before any
// later check relies on it, so e.g. the table CRC is computed only over a
// range already known to lie inside the file, and the first error found is
// the same for every conforming reader.
//
// Choices where the brief left room: the major version is checked right
// after the magic and before the header CRC, because a future major version
// may move the CRC; the layout must be canonical (each section and the table
// at the next 8-byte boundary, at most 7 zero padding bytes), so there is
// exactly one valid byte sequence for a given list of sections.
#include "formats/container/container_reader.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <set>

#include "formats/container/container_errors.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/support/crc32c.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status error(ContainerError code, const std::string& detail) {
  return container_error(code, detail);
}

std::string hex_bytes(const uint8_t* data, size_t count) {
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    if (i != 0) out.push_back(' ');
    out += string_printf("%02X", data[i]);
  }
  return out;
}

Status check_header(const uint8_t* data, size_t size, ContainerHeader* header) {
  const size_t prefix = size < sizeof(kContainerMagic) ? size : sizeof(kContainerMagic);
  if (prefix != 0 && std::memcmp(data, kContainerMagic, prefix) != 0) {
    return error(ContainerError::kBadMagic,
                 "not a lodbake container: file starts with " + hex_bytes(data, prefix) +
                     ", expected " + hex_bytes(kContainerMagic, sizeof(kContainerMagic)));
  }
  // Magic (8) + major (2) + minor (2): enough to tell the version.
  if (size < 12) {
    return error(
        ContainerError::kTooShort,
        string_printf("file has %zu bytes, a container header needs %zu", size, kHeaderSize));
  }
  uint16_t major;
  std::memcpy(&major, data + 8, sizeof(major));
  if (major != kFormatMajor) {
    return error(ContainerError::kUnsupportedMajor,
                 string_printf("format major version %u is not supported (this reader reads %u.x)",
                               major, kFormatMajor));
  }
  if (size < kHeaderSize) {
    return error(
        ContainerError::kTooShort,
        string_printf("file has %zu bytes, a container header needs %zu", size, kHeaderSize));
  }
  *header = decode_header(data);
  const uint32_t actual_crc = crc32c(data, kHeaderChecksummedBytes);
  if (actual_crc != header->header_crc32c) {
    return error(ContainerError::kHeaderChecksum,
                 string_printf("header checksum mismatch: stored 0x%08X, bytes 0..43 give 0x%08X",
                               header->header_crc32c, actual_crc));
  }
  if (header->minor > kFormatMinor) {
    return error(ContainerError::kNewerMinor,
                 string_printf("format version %u.%u is newer than this reader (%u.%u)",
                               header->major, header->minor, kFormatMajor, kFormatMinor));
  }
  if (header->flags != 0) {
    return error(
        ContainerError::kHeaderFlags,
        string_printf("unknown header flags 0x%08X (format 1.0 defines none)", header->flags));
  }
  if (header->reserved != 0) {
    return error(ContainerError::kHeaderFlags,
                 string_printf("header reserved field is 0x%08X, must be 0", header->reserved));
  }
  if (header->file_size > size) {
    return error(ContainerError::kTruncated,
                 string_printf("file is truncated: header says %" PRIu64 " bytes, file has %zu",
                               header->file_size, size));
  }
  if (header->file_size < size) {
    return error(
        ContainerError::kTrailingBytes,
        string_printf("%" PRIu64 " trailing bytes: header says %" PRIu64 " bytes, file has %zu",
                      static_cast<uint64_t>(size) - header->file_size, header->file_size, size));
  }
  if (header->table_offset < kHeaderSize || header->table_offset > header->file_size) {
    return error(ContainerError::kTableOutOfBounds,
                 string_printf("section table offset %" PRIu64 " is outside %zu..%" PRIu64,
                               header->table_offset, kHeaderSize, header->file_size));
  }
  if (header->table_offset % kSectionAlignment != 0) {
    return error(ContainerError::kTableOutOfBounds,
                 string_printf("section table offset %" PRIu64 " is not a multiple of 8",
                               header->table_offset));
  }
  // section_count < 2^32, so the product fits in 64 bits.
  const uint64_t table_bytes = header->file_size - header->table_offset;
  const uint64_t needed = uint64_t{header->section_count} * kTableEntrySize;
  if (needed != table_bytes) {
    return error(ContainerError::kBadSectionCount,
                 string_printf("section count %u needs %" PRIu64 " table bytes, but %" PRIu64
                               " bytes follow the table offset %" PRIu64,
                               header->section_count, needed, table_bytes, header->table_offset));
  }
  const uint32_t table_crc = crc32c(data + header->table_offset, static_cast<size_t>(table_bytes));
  if (table_crc != header->table_crc32c) {
    return error(
        ContainerError::kTableChecksum,
        string_printf("section table checksum mismatch: stored 0x%08X, the table's %" PRIu64
                      " bytes give 0x%08X",
                      header->table_crc32c, table_bytes, table_crc));
  }
  return Status::ok();
}

// Padding in [from, to) must be shorter than the alignment and all zero.
Status check_padding(const uint8_t* data, uint64_t from, uint64_t to, const std::string& before) {
  if (to - from >= kSectionAlignment) {
    return error(ContainerError::kBadPadding,
                 string_printf("%" PRIu64 " bytes between offset %" PRIu64 " and %s at %" PRIu64
                               ", at most 7 padding bytes allowed",
                               to - from, from, before.c_str(), to));
  }
  for (uint64_t i = from; i < to; ++i) {
    if (data[i] != 0) {
      return error(ContainerError::kBadPadding,
                   string_printf("nonzero padding byte 0x%02X at offset %" PRIu64 " before %s",
                                 data[i], i, before.c_str()));
    }
  }
  return Status::ok();
}

Status check_entries(const uint8_t* data, const ContainerHeader& header,
                     std::vector<Section>* sections) {
  const uint64_t area_end = header.table_offset;
  std::set<std::string> seen;
  uint64_t previous_end = kHeaderSize;
  uint32_t previous_group = 0;
  sections->reserve(header.section_count);
  for (uint32_t i = 0; i < header.section_count; ++i) {
    SectionEntry entry = decode_entry(data + header.table_offset + uint64_t{i} * kTableEntrySize);
    if (!is_valid_tag(entry.tag)) {
      return error(ContainerError::kBadTag,
                   string_printf("section %u tag \"%s\" is not 4 printable ASCII characters", i,
                                 printable_tag(entry.tag).c_str()));
    }
    const char* tag = entry.tag.c_str();
    if ((entry.flags & ~kKnownSectionFlags) != 0) {
      return error(ContainerError::kSectionFlags,
                   string_printf("section %s has unknown flags 0x%04X (format 1.x defines 0x0001)",
                                 tag, entry.flags));
    }
    if (entry.group != 0 && header.minor < kFirstMinorWithGroups) {
      return error(ContainerError::kSectionFlags,
                   string_printf("section %s reserved field is 0x%08X, must be 0 in format 1.%u",
                                 tag, entry.group, header.minor));
    }
    // Groups run 0, 1, 2, ... in table order, so a group's sections are
    // contiguous and the numbering is canonical.
    const uint64_t highest_next = i == 0 ? 0 : uint64_t{previous_group} + 1;
    if (entry.group < previous_group || entry.group > highest_next) {
      return error(ContainerError::kGroupOrder,
                   string_printf("section %u (%s) is in group %u after group %u: groups are "
                                 "numbered 0, 1, 2, ... in table order",
                                 i, tag, entry.group, i == 0 ? 0u : previous_group));
    }
    previous_group = entry.group;
    if (!seen.insert(std::to_string(entry.group) + ':' + entry.tag).second) {
      return error(ContainerError::kDuplicateTag,
                   entry.group == 0 ? string_printf("section %u repeats tag %s", i, tag)
                                    : string_printf("section %u repeats tag %s in group %u", i, tag,
                                                    entry.group));
    }
    if (entry.offset < kHeaderSize || entry.offset > area_end ||
        entry.stored_size > area_end - entry.offset) {
      return error(ContainerError::kSectionOutOfBounds,
                   string_printf("section %s (offset %" PRIu64 ", %" PRIu64
                                 " bytes) lies outside the section area %zu..%" PRIu64,
                                 tag, entry.offset, entry.stored_size, kHeaderSize, area_end));
    }
    if (entry.offset % kSectionAlignment != 0) {
      return error(
          ContainerError::kSectionMisaligned,
          string_printf("section %s offset %" PRIu64 " is not a multiple of 8", tag, entry.offset));
    }
    if (entry.offset < previous_end) {
      return error(ContainerError::kSectionOverlap,
                   string_printf("section %s at offset %" PRIu64
                                 " starts before the previous section ends (%" PRIu64 ")",
                                 tag, entry.offset, previous_end));
    }
    LODBAKE_RETURN_IF_ERROR(
        check_padding(data, previous_end, entry.offset, std::string("section ") + tag));
    previous_end = entry.offset + entry.stored_size;
    Section section;
    section.data = data + entry.offset;
    section.size = static_cast<size_t>(entry.stored_size);
    section.entry = std::move(entry);
    sections->push_back(std::move(section));
  }
  return check_padding(data, previous_end, area_end, "the section table");
}

Status check_contents(std::vector<Section>* sections, const std::vector<std::string>& known_tags) {
  for (Section& section : *sections) {
    const SectionEntry& entry = section.entry;
    const char* tag = entry.tag.c_str();
    const uint32_t actual = crc32c(section.data, section.size);
    if (actual != entry.crc32c) {
      return error(ContainerError::kSectionChecksum,
                   string_printf("section %s checksum mismatch: stored 0x%08X, its %" PRIu64
                                 " bytes give 0x%08X",
                                 tag, entry.crc32c, entry.stored_size, actual));
    }
    if (!codec_available(entry.codec)) {
      const char* name = codec_name(entry.codec);
      return error(ContainerError::kUnknownCodec,
                   name == nullptr
                       ? string_printf("section %s uses unknown codec %u (0 raw, 1 compact, "
                                       "2 draco)",
                                       tag, entry.codec)
                       : string_printf("section %s uses codec %u (%s), which this build cannot "
                                       "decode",
                                       tag, entry.codec, name));
    }
    // Only raw fixes the decoded size here; the others are checked once the
    // payload is decoded (formats/sections/section_payloads.h).
    if (entry.codec == static_cast<uint16_t>(SectionCodec::kRaw) &&
        entry.decoded_size != entry.stored_size) {
      return error(ContainerError::kSizeMismatch,
                   string_printf("section %s is raw but its decoded size %" PRIu64
                                 " differs from its stored size %" PRIu64,
                                 tag, entry.decoded_size, entry.stored_size));
    }
    for (const std::string& known : known_tags) {
      if (known == entry.tag) section.known = true;
    }
  }
  for (const Section& section : *sections) {
    if (section.required() && !section.known) {
      return error(
          ContainerError::kUnknownRequired,
          "section " + section.entry.tag + " is marked required but this reader does not know it");
    }
  }
  return Status::ok();
}

}  // namespace

const Section* Container::find(std::string_view tag, uint32_t group) const {
  for (const Section& section : sections) {
    if (section.entry.group == group && section.entry.tag == tag) return &section;
  }
  return nullptr;
}

Result<const Section*> Container::require(std::string_view tag, uint32_t group) const {
  const Section* section = find(tag, group);
  if (section == nullptr) {
    return container_error(
        ContainerError::kMissingSection,
        group == 0 ? "the container has no " + std::string(tag) + " section"
                   : "group " + std::to_string(group) + " has no " + std::string(tag) + " section");
  }
  return section;
}

Container single_group(const Container& container, uint32_t group) {
  Container out;
  out.header = container.header;
  for (const Section& section : container.sections) {
    if (section.group() != group) continue;
    out.sections.push_back(section);
    out.sections.back().entry.group = 0;
  }
  return out;
}

uint32_t Container::group_count() const {
  return sections.empty() ? 0 : sections.back().entry.group + 1;
}

Result<Container> read_container(const uint8_t* data, size_t size,
                                 const std::vector<std::string>& known_tags) {
  try {
    Container container;
    LODBAKE_RETURN_IF_ERROR(check_header(data, size, &container.header));
    LODBAKE_RETURN_IF_ERROR(check_entries(data, container.header, &container.sections));
    LODBAKE_RETURN_IF_ERROR(check_contents(&container.sections, known_tags));
    return container;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the container");
  }
}

Result<Container> read_container(const uint8_t* data, size_t size) {
  std::vector<std::string> known;
  for (const SectionKind& kind : known_section_kinds())
    known.emplace_back(kind.tag);
  return read_container(data, size, known);
}

}  // namespace lodbake
