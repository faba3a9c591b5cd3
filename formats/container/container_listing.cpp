// Lenient container listing. The verdict comes from the strict reader, so
// inspect's error and lodbake's other tools always agree; this file only
// gathers what can still be shown around the failure, clamping every range
// to the bytes actually present instead of rejecting it.
#include "formats/container/container_listing.h"

#include <new>

#include "formats/container/container_reader.h"
#include "formats/container/section_registry.h"
#include "formats/support/crc32c.h"

namespace lodbake {

ContainerListing list_container(const uint8_t* data, size_t size) {
  ContainerListing listing;
  listing.actual_size = size;
  try {
    Result<Container> strict = read_container(data, size);
    if (!strict.is_ok()) listing.status = strict.status();

    listing.magic_ok = starts_with_container_magic(data, size);
    if (size < kHeaderSize) return listing;
    listing.header_read = true;
    listing.header = decode_header(data);
    listing.header_crc_ok = crc32c(data, kHeaderChecksummedBytes) == listing.header.header_crc32c;

    // A different major version may lay the table out differently.
    const ContainerHeader& header = listing.header;
    if (!listing.magic_ok || header.major != kFormatMajor) return listing;
    if (header.table_offset < kHeaderSize || header.table_offset > size) return listing;
    listing.table_read = true;
    const uint64_t fit = (size - header.table_offset) / kTableEntrySize;
    const uint64_t count = fit < header.section_count ? fit : header.section_count;
    listing.table_complete = count == header.section_count;
    if (listing.table_complete) {
      listing.table_crc_ok =
          crc32c(data + header.table_offset, static_cast<size_t>(count * kTableEntrySize)) ==
          header.table_crc32c;
    }
    listing.sections.reserve(static_cast<size_t>(count));
    // Overlapping entries of a broken file could make checksumming quadratic;
    // a valid file's sections add up to less than its size, so that is the budget.
    uint64_t checksum_budget = size;
    for (uint64_t i = 0; i < count; ++i) {
      SectionListing section;
      section.entry = decode_entry(data + header.table_offset + i * kTableEntrySize);
      section.display_tag = printable_tag(section.entry.tag);
      section.known = is_known_section(section.entry.tag);
      const SectionEntry& entry = section.entry;
      section.in_file = entry.offset <= size && entry.stored_size <= size - entry.offset;
      if (section.in_file) {
        section.data = data + entry.offset;
        section.size = static_cast<size_t>(entry.stored_size);
      }
      if (section.in_file && entry.stored_size <= checksum_budget) {
        checksum_budget -= entry.stored_size;
        section.crc_checked = true;
        section.actual_crc32c = crc32c(section.data, section.size);
        section.crc_ok = section.actual_crc32c == entry.crc32c;
      }
      listing.sections.push_back(std::move(section));
    }
  } catch (const std::bad_alloc&) {
    listing.status = runtime_error("out of memory while listing the container");
  }
  return listing;
}

}  // namespace lodbake
