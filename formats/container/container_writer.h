// Building a lodbake container in memory. Write the result to disk with
// write_file_atomic() (formats/support/file_io.h), so a failed run never
// leaves a partial file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "formats/container/container_layout.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// Collects sections and lays them out as a format 1.0 container, or 1.1
/// when a section is in a group other than 0.
///
/// Output is a pure function of the sections added and their order: sections
/// appear in the order of add_section() calls, each at the next 8-byte
/// aligned offset after the header or the previous section with zero
/// padding, then the section table, which ends the file. No timestamps, no
/// pointer-dependent data, so two writers fed the same calls produce
/// byte-identical files.
class ContainerWriter {
 public:
  /// Adds a section to `group`. `required` sets flag bit 0: a reader that
  /// does not know `tag` must then refuse the whole file (use it for sections
  /// whose absence would make the file mean something else). Known tags must
  /// use the form without `required`; this one is for sections of other
  /// tools. Groups are added in order: `group` is the previous section's
  /// group or the next one (0 for the first section).
  /// \return LBK-E016 when `tag` is not 4 characters in 0x21..0x7E, LBK-E017
  ///         when a section with that tag was already added to the group,
  ///         LBK-E025 for a group out of order; nothing is added then.
  Status add_section(std::string_view tag, Bytes payload, bool required, uint32_t group = 0);

  /// Adds a section of a known tag with the required flag the registry gives
  /// it (section_required(), formats/container/section_registry.h), so every
  /// lodbake writer flags a tag alike.
  /// \return as above, or kInvalidInput when `tag` is not a known tag.
  Status add_known_section(std::string_view tag, Bytes payload, uint32_t group = 0);

  /// Adds a section whose stored bytes encode its payload with `codec`;
  /// `decoded_size` is the payload's size (for raw it must be stored.size()).
  /// \return as add_section(), or kInvalidInput for a raw section whose
  ///         decoded size differs from its stored size.
  Status add_stored_section(std::string_view tag, Bytes stored, SectionCodec codec,
                            uint64_t decoded_size, bool required, uint32_t group = 0);

  /// add_stored_section() of a known tag, with the registry's required flag.
  Status add_known_stored_section(std::string_view tag, Bytes stored, SectionCodec codec,
                                  uint64_t decoded_size, uint32_t group = 0);

  /// Number of sections added so far.
  size_t section_count() const { return sections_.size(); }

  /// The complete container. Does not change the writer (call it again for
  /// the same bytes). Fails with kRuntime only when memory runs out or the
  /// sections exceed the 2^32 - 1 entries a table can hold.
  Result<Bytes> finish() const;

  /// finish(), freeing each payload once it is copied in, so the container
  /// and its sections are not held twice (a large container's peak); the
  /// writer is left empty on success and unchanged on failure.
  Result<Bytes> finish_and_clear();

 private:
  struct Pending {
    std::string tag;
    Bytes payload;
    bool required;
    SectionCodec codec;
    uint64_t decoded_size;
    uint32_t group;
  };
  template <class Sections>
  static Result<Bytes> assemble(Sections& sections);

  std::vector<Pending> sections_;
};

}  // namespace lodbake
