// The one way a consumer opens a container: the strict reader's checks
// (container_reader.h), then every coded section decoded to its raw payload
// (section_payloads.h), so a tool parses the same payloads whatever codec
// lodbake-pack chose; and one wording for a structure the file lacks.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// A container that passed read_container() and whose coded sections all
/// decoded. It owns the file's bytes and the decoded payloads: moving it
/// keeps every Section valid.
class OpenedContainer {
 public:
  const ContainerHeader& header() const { return decoded_.header; }
  /// The sections in table order, each with its raw payload (data, size);
  /// entries keep the stored codec and sizes.
  const Container& decoded() const { return decoded_; }
  /// The same sections with their stored bytes, for tools that copy them.
  const Container& stored() const { return stored_; }
  uint32_t group_count() const { return decoded_.group_count(); }
  /// The raw payload of `tag` in `group`, or nullptr.
  const Section* find(std::string_view tag, uint32_t group = 0) const {
    return decoded_.find(tag, group);
  }
  /// The stored bytes of the section at the same place as `decoded`.
  const Section& stored_of(const Section& decoded) const;

  /// The first group holding every tag of `tags` (sections of one group
  /// describe one base mesh). Otherwise LBK-E024, one line: "the container
  /// has no VHIE section; mode vhier needs BASE + VHIE + RFIN
  /// (lodbake-hierarchy)" where `purpose` is "mode vhier" and `producer`
  /// the tool that writes them, or, when every tag is present but never all
  /// in one group, that no group holds them together.
  Result<uint32_t> group_with(const std::vector<const char*>& tags, const std::string& purpose,
                              const std::string& producer) const;

 private:
  friend Result<OpenedContainer> open_container(Bytes file);
  Bytes file_;
  Container stored_;
  Container decoded_;
  std::vector<Bytes> payloads_;
};

/// Checks `file` as read_container() does and decodes every coded section.
/// \return the strict reader's errors; LBK-E020 (kUnsupported) for a codec
///         this build lacks or that the section's kind does not define;
///         LBK-E021 / E023 / E024 from the codecs (decode_section_codecs()).
///         Never throws; out of memory is kRuntime.
Result<OpenedContainer> open_container(Bytes file);

/// Reads the file at `path` and opens it; read errors are kIo.
Result<OpenedContainer> open_container_file(const std::string& path);

}  // namespace lodbake
