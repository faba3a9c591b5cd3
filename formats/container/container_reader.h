// The strict container reader: accepts a format 1.0 or 1.1 container only when
// every byte of it checks out, and otherwise names the first problem with a
// stable LBK-E0nn error (formats/container/container_errors.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "formats/container/container_layout.h"
#include "formats/support/status.h"

namespace lodbake {

/// One section of a container that passed read_container().
struct Section {
  SectionEntry entry;             ///< the table entry (tag, codec, flags, sizes, CRC)
  const uint8_t* data = nullptr;  ///< the stored bytes, inside the caller's buffer
  size_t size = 0;                ///< == entry.stored_size
  bool known = false;             ///< the reader was told about this tag

  const std::string& tag() const { return entry.tag; }
  uint32_t group() const { return entry.group; }
  bool required() const { return entry.required(); }
};

/// A container that passed every check of read_container(). Sections point
/// into the buffer passed to read_container(): keep that buffer alive and
/// unchanged while using them.
struct Container {
  ContainerHeader header;
  std::vector<Section> sections;  ///< in table order, which is file order

  /// The section with `tag` in `group`, or nullptr.
  const Section* find(std::string_view tag, uint32_t group = 0) const;

  /// The section with `tag` in `group`, or LBK-E024 "missing section" for a
  /// caller that cannot work without it.
  Result<const Section*> require(std::string_view tag, uint32_t group = 0) const;

  /// How many groups the sections form (the last section's group + 1; 0
  /// without sections).
  uint32_t group_count() const;
};

/// The sections of `group` alone, as a container of one group (their group
/// field set to 0), for code that handles one base mesh and its structures.
/// The sections still point into the original buffers.
Container single_group(const Container& container, uint32_t group);

/// Parses and checks a container of `size` bytes at `data`, knowing the tags
/// of the section registry (section_registry.h).
///
/// Checks, in this order, each before anything depends on it (arithmetic on
/// file values is overflow-safe): magic, length, major version, header CRC,
/// minor version, header flags and reserved field, file size against `size`,
/// table position and alignment, section count against the table size,
/// table CRC; then per entry: tag characters, flags, group (0 before format
/// 1.1; numbered 0, 1, 2, ... in table order), tag uniqueness in its group, bounds within [48,
/// table_offset), 8-byte alignment, order and overlap, padding (at most 7 zero bytes before each
/// section and before the table); then per section: CRC of the stored bytes, codec, decoded size;
/// finally that no required section has an unknown tag. Unknown optional sections are accepted and
/// returned with known == false. Section payloads are not decoded: that is each section's decoder's
/// job.
///
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the container, or the first failed check as a Status whose code()
///         is the LBK error number and whose kind is kUnsupported for
///         LBK-E004, E005 and E020 and kInvalidInput otherwise. Never throws,
///         never reads outside [data, data + size), allocates at most
///         O(size) memory.
Result<Container> read_container(const uint8_t* data, size_t size);

/// As above, but the known tags are exactly `known_tags` (the registry is
/// not consulted). Useful for tools that handle a subset or a superset.
Result<Container> read_container(const uint8_t* data, size_t size,
                                 const std::vector<std::string>& known_tags);

}  // namespace lodbake
