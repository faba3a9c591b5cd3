// Byte-exact encoding of the container header and section-table entries
// (little-endian, fixed offsets; docs/format.md "Header" and "Section table").
#include "formats/container/container_layout.h"

#include <cstdio>
#include <cstring>

#include "formats/support/byte_reader.h"
#include "formats/support/crc32c.h"

namespace lodbake {
namespace {

template <typename T>
void put(uint8_t* out, size_t offset, T value) {
  std::memcpy(out + offset, &value, sizeof(T));  // the host is little-endian (byte_reader.h)
}

template <typename T>
void get(const uint8_t* data, size_t offset, T* value) {
  std::memcpy(value, data + offset, sizeof(T));
}

// The byte offset of every fixed-width field, listed once so that encoding
// and decoding cannot disagree. `Header` is ContainerHeader, const or not;
// the magic (bytes 0..7) and the header CRC (bytes 44..47, computed when
// encoding) are handled by the callers.
template <typename Header, typename Visit>
void header_fields(Header& header, Visit visit) {
  visit(8, header.major);
  visit(10, header.minor);
  visit(12, header.flags);
  visit(16, header.file_size);
  visit(24, header.table_offset);
  visit(32, header.section_count);
  visit(36, header.table_crc32c);
  visit(40, header.reserved);
}

// The same for a section-table entry; the tag (bytes 0..3) is the callers'.
template <typename Entry, typename Visit>
void entry_fields(Entry& entry, Visit visit) {
  visit(4, entry.codec);
  visit(6, entry.flags);
  visit(8, entry.offset);
  visit(16, entry.stored_size);
  visit(24, entry.decoded_size);
  visit(32, entry.crc32c);
  visit(36, entry.group);
}

}  // namespace

void encode_header(const ContainerHeader& header, uint8_t* out) {
  std::memcpy(out, kContainerMagic, sizeof(kContainerMagic));
  header_fields(header, [out](size_t offset, auto value) { put(out, offset, value); });
  put<uint32_t>(out, 44, crc32c(out, kHeaderChecksummedBytes));
}

ContainerHeader decode_header(const uint8_t* data) {
  ContainerHeader header;
  header_fields(header, [data](size_t offset, auto& field) { get(data, offset, &field); });
  get(data, 44, &header.header_crc32c);
  return header;
}

void encode_entry(const SectionEntry& entry, uint8_t* out) {
  std::memcpy(out, entry.tag.data(), 4);
  entry_fields(entry, [out](size_t offset, auto value) { put(out, offset, value); });
}

SectionEntry decode_entry(const uint8_t* data) {
  SectionEntry entry;
  entry.tag.assign(reinterpret_cast<const char*>(data), 4);
  entry_fields(entry, [data](size_t offset, auto& field) { get(data, offset, &field); });
  return entry;
}

bool is_valid_tag(std::string_view tag) {
  if (tag.size() != 4) return false;
  for (char c : tag) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x21 || byte > 0x7E) return false;
  }
  return true;
}

std::string printable_tag(std::string_view tag) {
  std::string out;
  for (char c : tag) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x21 && byte <= 0x7E && byte != '\\') {
      out.push_back(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02X", byte);
      out += escaped;
    }
  }
  return out;
}

uint64_t align_up8(uint64_t value) {
  if (value > UINT64_MAX - (kSectionAlignment - 1)) return UINT64_MAX;
  return (value + kSectionAlignment - 1) & ~(kSectionAlignment - 1);
}

}  // namespace lodbake
