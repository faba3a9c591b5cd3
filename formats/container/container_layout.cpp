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
T get(const uint8_t* data, size_t offset) {
  T value;
  std::memcpy(&value, data + offset, sizeof(T));
  return value;
}

}  // namespace

void encode_header(const ContainerHeader& header, uint8_t* out) {
  std::memcpy(out, kContainerMagic, sizeof(kContainerMagic));
  put<uint16_t>(out, 8, header.major);
  put<uint16_t>(out, 10, header.minor);
  put<uint32_t>(out, 12, header.flags);
  put<uint64_t>(out, 16, header.file_size);
  put<uint64_t>(out, 24, header.table_offset);
  put<uint32_t>(out, 32, header.section_count);
  put<uint32_t>(out, 36, header.table_crc32c);
  put<uint32_t>(out, 40, header.reserved);
  put<uint32_t>(out, 44, crc32c(out, kHeaderChecksummedBytes));
}

ContainerHeader decode_header(const uint8_t* data) {
  ContainerHeader header;
  header.major = get<uint16_t>(data, 8);
  header.minor = get<uint16_t>(data, 10);
  header.flags = get<uint32_t>(data, 12);
  header.file_size = get<uint64_t>(data, 16);
  header.table_offset = get<uint64_t>(data, 24);
  header.section_count = get<uint32_t>(data, 32);
  header.table_crc32c = get<uint32_t>(data, 36);
  header.reserved = get<uint32_t>(data, 40);
  header.header_crc32c = get<uint32_t>(data, 44);
  return header;
}

void encode_entry(const SectionEntry& entry, uint8_t* out) {
  std::memcpy(out, entry.tag.data(), 4);
  put<uint16_t>(out, 4, entry.codec);
  put<uint16_t>(out, 6, entry.flags);
  put<uint64_t>(out, 8, entry.offset);
  put<uint64_t>(out, 16, entry.stored_size);
  put<uint64_t>(out, 24, entry.decoded_size);
  put<uint32_t>(out, 32, entry.crc32c);
  put<uint32_t>(out, 36, entry.reserved);
}

SectionEntry decode_entry(const uint8_t* data) {
  SectionEntry entry;
  entry.tag.assign(reinterpret_cast<const char*>(data), 4);
  entry.codec = get<uint16_t>(data, 4);
  entry.flags = get<uint16_t>(data, 6);
  entry.offset = get<uint64_t>(data, 8);
  entry.stored_size = get<uint64_t>(data, 16);
  entry.decoded_size = get<uint64_t>(data, 24);
  entry.crc32c = get<uint32_t>(data, 32);
  entry.reserved = get<uint32_t>(data, 36);
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
