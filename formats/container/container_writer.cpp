// Container writer: lays sections out in call order at 8-byte aligned
// offsets with minimal zero padding, then appends the table. This is the
// only layout the strict reader accepts (docs/format.md "Layout"), which is
// what makes a file's bytes a function of its sections alone.
#include "formats/container/container_writer.h"

#include <algorithm>
#include <new>
#include <type_traits>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/crc32c.h"

namespace lodbake {

Status ContainerWriter::add_section(std::string_view tag, Bytes payload, bool required,
                                    uint32_t group) {
  const uint64_t size = payload.size();
  return add_stored_section(tag, std::move(payload), SectionCodec::kRaw, size, required, group);
}

Status ContainerWriter::add_known_section(std::string_view tag, Bytes payload, uint32_t group) {
  const uint64_t size = payload.size();
  return add_known_stored_section(tag, std::move(payload), SectionCodec::kRaw, size, group);
}

Status ContainerWriter::add_known_stored_section(std::string_view tag, Bytes stored,
                                                 SectionCodec codec, uint64_t decoded_size,
                                                 uint32_t group) {
  if (!is_known_section(tag)) {
    return invalid_input("section " + printable_tag(tag) +
                         " is not a known tag: its required flag must be given");
  }
  return add_stored_section(tag, std::move(stored), codec, decoded_size, section_required(tag),
                            group);
}

Status ContainerWriter::add_stored_section(std::string_view tag, Bytes stored, SectionCodec codec,
                                           uint64_t decoded_size, bool required, uint32_t group) {
  if (codec == SectionCodec::kRaw && decoded_size != stored.size()) {
    return invalid_input("raw section " + printable_tag(tag) + " with a decoded size of " +
                         std::to_string(decoded_size) + " bytes and " +
                         std::to_string(stored.size()) + " stored");
  }
  if (!is_valid_tag(tag)) {
    return container_error(ContainerError::kBadTag,
                           "section tag \"" + printable_tag(tag) +
                               "\" is not 4 printable ASCII characters (0x21..0x7E)");
  }
  const uint32_t previous = sections_.empty() ? 0 : sections_.back().group;
  if (group < previous || group > (sections_.empty() ? 0 : uint64_t{previous} + 1)) {
    return container_error(ContainerError::kGroupOrder,
                           "section " + std::string(tag) + " added to group " +
                               std::to_string(group) + " after group " + std::to_string(previous));
  }
  for (const Pending& pending : sections_) {
    if (pending.tag == tag && pending.group == group) {
      return container_error(ContainerError::kDuplicateTag,
                             "section " + std::string(tag) + " was already added");
    }
  }
  sections_.push_back(
      Pending{std::string(tag), std::move(stored), required, codec, decoded_size, group});
  return Status::ok();
}

Result<Bytes> ContainerWriter::finish() const {
  return assemble(sections_);
}

Result<Bytes> ContainerWriter::finish_and_clear() {
  Result<Bytes> out = assemble(sections_);
  if (out.is_ok()) sections_.clear();
  return out;
}

// `Sections` is const for finish(); otherwise each payload is freed once
// copied (nothing allocates after the container's buffer, so a failure
// leaves the payloads as they were).
template <class Sections>
Result<Bytes> ContainerWriter::assemble(Sections& sections) {
  if (sections.size() > UINT32_MAX) {
    return runtime_error("too many sections for one container table");
  }
  try {
    std::vector<SectionEntry> entries;
    entries.reserve(sections.size());
    uint64_t end = kHeaderSize;
    for (const Pending& pending : sections) {
      SectionEntry entry;
      entry.tag = pending.tag;
      entry.codec = static_cast<uint16_t>(pending.codec);
      entry.flags = pending.required ? kSectionFlagRequired : 0;
      entry.offset = align_up8(end);
      entry.stored_size = pending.payload.size();
      entry.decoded_size = pending.decoded_size;
      entry.crc32c = crc32c(pending.payload.data(), pending.payload.size());
      entry.group = pending.group;
      end = entry.offset + entry.stored_size;
      entries.push_back(std::move(entry));
    }
    ContainerHeader header;
    // The lowest version the sections need: 1.0 files stay byte-identical.
    const bool grouped = !sections.empty() && sections.back().group != 0;
    header.minor = grouped ? kFirstMinorWithGroups : 0;
    header.table_offset = align_up8(end);
    header.section_count = static_cast<uint32_t>(entries.size());
    header.file_size = header.table_offset + entries.size() * kTableEntrySize;

    Bytes out(static_cast<size_t>(header.file_size), 0);
    for (size_t i = 0; i < entries.size(); ++i) {
      const Bytes& payload = sections[i].payload;
      if (!payload.empty()) {
        std::copy(payload.begin(), payload.end(),
                  out.begin() + static_cast<std::ptrdiff_t>(entries[i].offset));
      }
      if constexpr (!std::is_const_v<Sections>) Bytes().swap(sections[i].payload);
      encode_entry(entries[i],
                   out.data() + static_cast<size_t>(header.table_offset) + i * kTableEntrySize);
    }
    header.table_crc32c = crc32c(out.data() + static_cast<size_t>(header.table_offset),
                                 entries.size() * kTableEntrySize);
    encode_header(header, out.data());
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while assembling the container");
  }
}

}  // namespace lodbake
