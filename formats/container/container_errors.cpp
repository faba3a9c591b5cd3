// Numbered container errors: the id and kind of each, in one place, so that
// the reader, the section decoders and docs/format.md cannot drift apart.
#include "formats/container/container_errors.h"

#include <cstdio>

namespace lodbake {

std::string container_error_id(ContainerError error) {
  char id[16];
  std::snprintf(id, sizeof(id), "LBK-E%03d", static_cast<int>(error));
  return id;
}

const char* container_error_summary(ContainerError error) {
  switch (error) {
    case ContainerError::kTooShort:
      return "file is too short for a container header";
    case ContainerError::kBadMagic:
      return "not a lodbake container (bad magic)";
    case ContainerError::kHeaderChecksum:
      return "header checksum mismatch";
    case ContainerError::kUnsupportedMajor:
      return "unsupported major format version";
    case ContainerError::kNewerMinor:
      return "newer minor format version than this reader";
    case ContainerError::kHeaderFlags:
      return "unknown header flags or nonzero reserved field";
    case ContainerError::kTruncated:
      return "file is truncated";
    case ContainerError::kTrailingBytes:
      return "trailing bytes after the end of the container";
    case ContainerError::kTableOutOfBounds:
      return "section table out of bounds";
    case ContainerError::kBadSectionCount:
      return "section count does not match the table size";
    case ContainerError::kTableChecksum:
      return "section table checksum mismatch";
    case ContainerError::kSectionOutOfBounds:
      return "section out of bounds";
    case ContainerError::kSectionMisaligned:
      return "section not 8-byte aligned";
    case ContainerError::kSectionOverlap:
      return "sections overlap or are out of order";
    case ContainerError::kBadPadding:
      return "bad padding between sections";
    case ContainerError::kBadTag:
      return "section tag is not printable ASCII";
    case ContainerError::kDuplicateTag:
      return "duplicate section tag in a group";
    case ContainerError::kSectionFlags:
      return "unknown section flags or nonzero reserved field";
    case ContainerError::kSectionChecksum:
      return "section checksum mismatch";
    case ContainerError::kUnknownCodec:
      return "unsupported section codec";
    case ContainerError::kSizeMismatch:
      return "section decoded size mismatch";
    case ContainerError::kUnknownRequired:
      return "unknown required section";
    case ContainerError::kMalformedSection:
      return "malformed section payload";
    case ContainerError::kMissingSection:
      return "missing section";
    case ContainerError::kGroupOrder:
      return "section groups out of order";
  }
  return "unknown error";
}

Status container_error(ContainerError error, const std::string& detail) {
  const bool is_unsupported = error == ContainerError::kUnsupportedMajor ||
                              error == ContainerError::kNewerMinor ||
                              error == ContainerError::kUnknownCodec;
  std::string message = container_error_id(error) + ": " + detail;
  const int code = static_cast<int>(error);
  return is_unsupported ? unsupported(std::move(message), code)
                        : invalid_input(std::move(message), code);
}

Status malformed_section(const char* tag, const std::string& detail) {
  return container_error(ContainerError::kMalformedSection,
                         std::string("section ") + tag + ": " + detail);
}

}  // namespace lodbake
