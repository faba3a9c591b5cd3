// A lenient view of a possibly broken container, for `lodbake-inspect`:
// everything that can be read is reported, next to the first error the
// strict reader finds. Never use a listing to decide whether to trust a
// file; use read_container() for that.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/container/container_layout.h"
#include "formats/support/status.h"

namespace lodbake {

/// One table entry as found in the file, with what could be checked about it.
struct SectionListing {
  SectionEntry entry;             ///< fields as stored (the tag may hold unprintable bytes)
  std::string display_tag;        ///< printable_tag(entry.tag)
  bool known = false;             ///< the tag is in the section registry
  bool in_file = false;           ///< offset + stored_size lies inside the bytes given
  const uint8_t* data = nullptr;  ///< the stored bytes when in_file, else nullptr
  size_t size = 0;                ///< entry.stored_size when in_file, else 0
  /// in_file and the CRC was computed. Not computed for entries past the
  /// point where the listed sections add up to more bytes than the file
  /// (overlapping entries of a broken file), which keeps listing O(size).
  bool crc_checked = false;
  bool crc_ok = false;         ///< crc_checked and it matched entry.crc32c
  uint32_t actual_crc32c = 0;  ///< the computed CRC when crc_checked
};

/// Whatever could be read of a container.
struct ContainerListing {
  uint64_t actual_size = 0;  ///< bytes given to list_container()
  bool magic_ok = false;     ///< the file starts with the container magic
  bool header_read = false;  ///< at least 48 bytes: `header` holds the stored fields
  ContainerHeader header;    ///< valid when header_read (even if its CRC is wrong)
  bool header_crc_ok = false;
  /// The table could be located: magic and major version match and the
  /// table offset lies inside the bytes given. Entries that fit inside the
  /// bytes given are listed (at most section_count of them).
  bool table_read = false;
  bool table_complete = false;           ///< all section_count entries were listed
  bool table_crc_ok = false;             ///< table_complete and the table CRC matched
  std::vector<SectionListing> sections;  ///< in table order
  /// The first error of read_container() with the registry's tags; ok when
  /// the file is valid. Its message is what inspect prints as the error.
  Status status;
};

/// Lists a container leniently. Never fails and never throws: every field it
/// cannot read is marked so. Does not decode section payloads.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// Memory is O(size) even for hostile input (the entries listed all lie in
/// the bytes given).
ContainerListing list_container(const uint8_t* data, size_t size);

}  // namespace lodbake
