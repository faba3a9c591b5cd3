// The stable numbered errors of the lodbake container ("LBK-E001" ...). The
// numbers are part of the format's documentation (docs/format.md, "Error
// codes"): never renumber or reuse one, only append.
#pragma once

#include <string>

#include "formats/support/status.h"

namespace lodbake {

/// Every container error. The value is the number after "LBK-E" and the
/// Status::code() of the error.
enum class ContainerError : int {
  kTooShort = 1,             // fewer bytes than the 48-byte header (or its first fields)
  kBadMagic = 2,             // not a lodbake container
  kHeaderChecksum = 3,       // header CRC-32C mismatch
  kUnsupportedMajor = 4,     // major version other than 1 (kUnsupported)
  kNewerMinor = 5,           // minor version newer than this reader (kUnsupported)
  kHeaderFlags = 6,          // unknown header flag bits or nonzero reserved field
  kTruncated = 7,            // file shorter than the header's file_size
  kTrailingBytes = 8,        // file longer than the header's file_size
  kTableOutOfBounds = 9,     // table offset before the sections' area, past the end or misaligned
  kBadSectionCount = 10,     // section count does not fill the table exactly to the end
  kTableChecksum = 11,       // section table CRC-32C mismatch
  kSectionOutOfBounds = 12,  // section outside [48, table_offset) or its end overflows
  kSectionMisaligned = 13,   // section offset not a multiple of 8
  kSectionOverlap = 14,      // section starts before the previous one ends (or out of order)
  kBadPadding = 15,          // padding between sections is nonzero or longer than 7 bytes
  kBadTag = 16,              // tag bytes outside printable ASCII 0x21..0x7E
  kDuplicateTag = 17,        // two sections with the same tag in one group
  kSectionFlags = 18,        // unknown section flag bits or nonzero reserved field
  kSectionChecksum = 19,     // section CRC-32C mismatch
  kUnknownCodec = 20,        // codec other than raw (kUnsupported)
  kSizeMismatch = 21,        // decoded size disagrees with the stored size for the codec
  kUnknownRequired = 22,     // a section flagged required has a tag this reader does not know
  kMalformedSection = 23,    // a section's payload does not decode
  kMissingSection = 24,      // a section the caller needs is absent
  kGroupOrder = 25,          // section groups not numbered 0, 1, 2, ... in table order
};

/// The highest error number in use (the table in docs/format.md ends there).
inline constexpr int kLastContainerError = 25;

/// "LBK-E007" for kTruncated.
std::string container_error_id(ContainerError error);

/// A short fixed description of the error kind ("file is truncated"); what
/// docs/format.md lists and `lodbake-inspect --json` can report.
const char* container_error_summary(ContainerError error);

/// The Status for an error: kind kUnsupported for kUnsupportedMajor,
/// kNewerMinor and kUnknownCodec, kInvalidInput for all others; code() is the
/// error number; message is "LBK-E0nn: <detail>".
/// \pre `detail` is one line starting lower-case and does not name the file.
Status container_error(ContainerError error, const std::string& detail);

/// The LBK-E023 error of a section decoder: "LBK-E023: section BASE: <detail>".
Status malformed_section(const char* tag, const std::string& detail);

}  // namespace lodbake
