// The fixed binary layout of a lodbake container, version 1.1: constants,
// the header and the section-table entry as plain structs, and their
// byte-exact encoding. No validation here; that is the reader's job
// (container_reader.h). Specification: docs/format.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace lodbake {

/// File signature, PNG style: a high byte (catches 7-bit transfers), the
/// name, CR LF (catches line-ending conversion), ^Z (stops DOS `type`), LF.
inline constexpr uint8_t kContainerMagic[8] = {0x89, 'L', 'B', 'K', '\r', '\n', 0x1A, '\n'};

/// True when `data` starts with kContainerMagic.
inline bool starts_with_container_magic(const uint8_t* data, size_t size) {
  if (size < sizeof(kContainerMagic)) return false;
  for (size_t i = 0; i < sizeof(kContainerMagic); ++i) {
    if (data[i] != kContainerMagic[i]) return false;
  }
  return true;
}

inline constexpr uint16_t kFormatMajor = 1;
/// The newest minor version this build reads. Writers write the lowest
/// version their sections need: 1.0 unless a section is in a group other
/// than 0 (groups came with 1.1).
inline constexpr uint16_t kFormatMinor = 1;
/// The first minor version with section groups (the entry's last field).
inline constexpr uint16_t kFirstMinorWithGroups = 1;
inline constexpr size_t kHeaderSize = 48;
inline constexpr size_t kHeaderChecksummedBytes = 44;  // the header CRC covers bytes 0..43
inline constexpr size_t kTableEntrySize = 40;
inline constexpr uint64_t kSectionAlignment = 8;

/// Section flag bit 0: a reader that does not know the tag must refuse the file.
inline constexpr uint16_t kSectionFlagRequired = 0x0001;
/// All section flag bits defined by format 1.0.
inline constexpr uint16_t kKnownSectionFlags = kSectionFlagRequired;

/// How a section's stored bytes encode its payload (docs/format.md "Codecs"):
/// raw (stored bytes == payload), lodbake's compact coding of the section
/// kind, or a Draco bitstream. Other values are reserved.
enum class SectionCodec : uint16_t { kRaw = 0, kCompact = 1, kDraco = 2 };

/// The 48-byte header, field by field in file order.
struct ContainerHeader {
  uint16_t major = kFormatMajor;
  uint16_t minor = kFormatMinor;
  uint32_t flags = 0;
  uint64_t file_size = 0;
  uint64_t table_offset = 0;
  uint32_t section_count = 0;
  uint32_t table_crc32c = 0;
  uint32_t reserved = 0;
  uint32_t header_crc32c = 0;
};

/// One 40-byte section-table entry, field by field in file order.
struct SectionEntry {
  std::string tag;  ///< exactly the 4 stored bytes (may be unprintable in a broken file)
  uint16_t codec = 0;
  uint16_t flags = 0;
  uint64_t offset = 0;
  uint64_t stored_size = 0;
  uint64_t decoded_size = 0;
  uint32_t crc32c = 0;  ///< CRC-32C of the stored bytes
  /// The section's group (format 1.1; 0 in 1.0 files, where the field is
  /// reserved): the sections of one group describe one base mesh, the
  /// group's BASE, so one file can hold structures over several base
  /// meshes. Groups are numbered 0, 1, 2, ... in table order.
  uint32_t group = 0;

  bool required() const { return (flags & kSectionFlagRequired) != 0; }
};

/// Writes `header` into 48 bytes at `out`, with header_crc32c recomputed over
/// bytes 0..43 (the field's value in `header` is ignored).
void encode_header(const ContainerHeader& header, uint8_t* out);

/// Reads the header fields from 48 bytes at `data` as stored; checks nothing.
/// \pre `data` points to at least kHeaderSize readable bytes.
ContainerHeader decode_header(const uint8_t* data);

/// Writes `entry` into 40 bytes at `out`.
/// \pre entry.tag has exactly 4 bytes.
void encode_entry(const SectionEntry& entry, uint8_t* out);

/// Reads an entry's fields from 40 bytes at `data` as stored; checks nothing.
/// \pre `data` points to at least kTableEntrySize readable bytes.
SectionEntry decode_entry(const uint8_t* data);

/// True when `tag` is exactly 4 bytes, each printable ASCII other than space
/// (0x21..0x7E).
bool is_valid_tag(std::string_view tag);

/// `tag` for messages: printable bytes as they are, others as \xNN.
std::string printable_tag(std::string_view tag);

/// `value` rounded up to a multiple of 8, or UINT64_MAX when that overflows.
uint64_t align_up8(uint64_t value);

}  // namespace lodbake
