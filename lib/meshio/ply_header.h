// The header of a PLY file (Turk's format as documented with the Stanford
// ply library): format line, elements with their counts, scalar and list
// properties. Parsed separately from the body so that the body readers can
// work from a validated plan.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/status.h"

namespace lodbake {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// The eight PLY scalar types; both spellings (char / int8, float / float32,
// ...) map onto these.
enum class PlyType : uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

/// Size in bytes of one binary value of `type`.
size_t ply_type_size(PlyType type);
bool ply_type_is_integer(PlyType type);
/// The canonical name used in messages ("uchar", "float", ...).
const char* ply_type_name(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // for a list: the type of its entries
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // for a list: the type of its length (an integer type)
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  uint32_t line = 0;  // header line that declares it, for messages

  /// The property called `name`, or -1.
  int find(const std::string& name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;        // first byte after the end_header line
  uint32_t body_first_line = 0;  // line number of that byte (1-based)
};

/// Parses the header of the PLY file in `data`. Fails (kInvalidInput) on a
/// missing "ply" magic, a missing or repeated format line, unknown keywords
/// or types, a property outside an element, repeated element or property
/// names, malformed counts and a missing end_header line; kUnsupported on a
/// format version other than 1.0.
Result<PlyHeader> parse_ply_header(const uint8_t* data, size_t size);

}  // namespace lodbake
