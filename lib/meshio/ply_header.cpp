// PLY header parser. Choices where the format description is loose:
// - Lines end with "\n" or "\r\n"; words are separated by spaces or tabs.
// - The first line must be exactly "ply". "format" may appear once, anywhere
//   before end_header (some writers put comments first); only version 1.0
//   ("1.0" or "1") exists.
// - comment and obj_info lines are ignored.
// - Element and property names must be unique within their scope, since a
//   repeated "x" or a second "vertex" element would make the file ambiguous.
// - A list's length type must be an integer type.
// The header is bounded by the file (every line is inside `data`), so the
// number of elements and properties needs no separate limit.
#include "lib/meshio/ply_header.h"

#include <charconv>
#include <cstring>
#include <string_view>

namespace lodbake {
namespace {

struct TypeName {
  const char* name;
  PlyType type;
};

constexpr TypeName kTypeNames[] = {
    {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
    {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
    {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
    {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
    {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
    {"float64", PlyType::kFloat64}};

bool parse_type(std::string_view word, PlyType* type) {
  for (const TypeName& t : kTypeNames) {
    if (word == t.name) {
      *type = t.type;
      return true;
    }
  }
  return false;
}

// Splits a header line into at most kMaxWords words; `count` says how many
// the line had (capped at kMaxWords + 1 so that "too many" is detectable).
constexpr size_t kMaxWords = 6;
struct Words {
  std::string_view word[kMaxWords];
  size_t count = 0;
};

Words split_words(std::string_view line) {
  Words words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    if (i == line.size()) break;
    size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t')
      ++i;
    if (words.count < kMaxWords) words.word[words.count] = line.substr(start, i - start);
    ++words.count;
    if (words.count > kMaxWords) break;
  }
  return words;
}

std::string at_line(uint32_t line) {
  return "line " + std::to_string(line) + ": ";
}

// Keeps messages one line and short when a header word is binary garbage.
std::string quoted(std::string_view word) {
  std::string out = "'";
  for (char c : word.substr(0, 40))
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (word.size() > 40) out += "...";
  return out + "'";
}

bool contains_end_header(const uint8_t* data, size_t size) {
  static constexpr char kNeedle[] = "end_header";
  const size_t n = sizeof(kNeedle) - 1;
  for (size_t i = 0; i + n <= size; ++i) {
    if (std::memcmp(data + i, kNeedle, n) == 0) return true;
  }
  return false;
}

}  // namespace

size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType type) {
  return type != PlyType::kFloat32 && type != PlyType::kFloat64;
}

const char* ply_type_name(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
      return "char";
    case PlyType::kUint8:
      return "uchar";
    case PlyType::kInt16:
      return "short";
    case PlyType::kUint16:
      return "ushort";
    case PlyType::kInt32:
      return "int";
    case PlyType::kUint32:
      return "uint";
    case PlyType::kFloat32:
      return "float";
    case PlyType::kFloat64:
      return "double";
  }
  return "?";
}

int PlyElement::find(const std::string& property_name) const {
  for (size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property_name) return static_cast<int>(i);
  }
  return -1;
}

Result<PlyHeader> parse_ply_header(const uint8_t* data, size_t size) {
  if (size == 0) return invalid_input("empty file: no 'ply' magic line");
  PlyHeader header;
  bool have_format = false;
  size_t pos = 0;
  uint32_t line_number = 0;
  for (;;) {
    if (pos >= size) {
      return invalid_input(line_number <= 1 ? "bad magic: the file does not start with a 'ply' line"
                                            : "the header has no 'end_header' line");
    }
    ++line_number;
    const char* begin = reinterpret_cast<const char*>(data + pos);
    const void* newline = std::memchr(begin, '\n', size - pos);
    size_t length = newline != nullptr ? static_cast<const char*>(newline) - begin : size - pos;
    pos += length + (newline != nullptr ? 1 : 0);
    std::string_view line(begin, length);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

    if (line_number == 1) {
      if (line != "ply")
        return invalid_input("bad magic: the file does not start with a 'ply' line");
      continue;
    }
    Words words = split_words(line);
    if (words.count == 0) continue;
    std::string_view keyword = words.word[0];
    if (keyword == "comment" || keyword == "obj_info") continue;

    if (keyword == "end_header") {
      if (words.count != 1) return invalid_input(at_line(line_number) + "text after 'end_header'");
      if (!have_format) return invalid_input("the header has no 'format' line");
      header.body_offset = pos;
      header.body_first_line = line_number + 1;
      return header;
    }
    if (keyword == "format") {
      if (have_format) return invalid_input(at_line(line_number) + "a second 'format' line");
      if (words.count != 3) {
        return invalid_input(at_line(line_number) +
                             "'format' needs a format name and a version, e.g. 'format ascii 1.0'");
      }
      std::string_view name = words.word[1];
      if (name == "ascii") {
        header.format = PlyFormat::kAscii;
      } else if (name == "binary_little_endian") {
        header.format = PlyFormat::kBinaryLittleEndian;
      } else if (name == "binary_big_endian") {
        header.format = PlyFormat::kBinaryBigEndian;
      } else {
        return invalid_input(at_line(line_number) + "unknown format " + quoted(name) +
                             " (ascii, binary_little_endian or binary_big_endian)");
      }
      if (words.word[2] != "1.0" && words.word[2] != "1") {
        return unsupported(at_line(line_number) + "ply version " + quoted(words.word[2]) +
                           " (only 1.0 is defined)");
      }
      have_format = true;
      continue;
    }
    if (keyword == "element") {
      if (words.count != 3) {
        return invalid_input(at_line(line_number) + "'element' needs a name and a count");
      }
      PlyElement element;
      element.name = std::string(words.word[1]);
      element.line = line_number;
      std::string_view count = words.word[2];
      auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (ec != std::errc() || end != count.data() + count.size()) {
        return invalid_input(at_line(line_number) + "element " + quoted(element.name) + " count " +
                             quoted(count) + " is not a non-negative integer" +
                             (ec == std::errc::result_out_of_range ? " below 2^64" : ""));
      }
      for (const PlyElement& other : header.elements) {
        if (other.name == element.name) {
          return invalid_input(at_line(line_number) + "element " + quoted(element.name) +
                               " is declared twice");
        }
      }
      header.elements.push_back(std::move(element));
      continue;
    }
    if (keyword == "property") {
      if (header.elements.empty()) {
        return invalid_input(at_line(line_number) + "'property' before any 'element'");
      }
      PlyProperty property;
      if (words.count >= 2 && words.word[1] == "list") {
        if (words.count != 5) {
          return invalid_input(at_line(line_number) +
                               "'property list' needs a length type, an entry type and a name");
        }
        property.is_list = true;
        if (!parse_type(words.word[2], &property.count_type)) {
          return invalid_input(at_line(line_number) + "unknown list length type " +
                               quoted(words.word[2]));
        }
        if (!ply_type_is_integer(property.count_type)) {
          return invalid_input(at_line(line_number) + "list length type " + quoted(words.word[2]) +
                               " is not an integer type");
        }
        if (!parse_type(words.word[3], &property.type)) {
          return invalid_input(at_line(line_number) + "unknown list entry type " +
                               quoted(words.word[3]));
        }
        property.name = std::string(words.word[4]);
      } else {
        if (words.count != 3) {
          return invalid_input(at_line(line_number) + "'property' needs a type and a name");
        }
        if (!parse_type(words.word[1], &property.type)) {
          return invalid_input(at_line(line_number) + "unknown property type " +
                               quoted(words.word[1]));
        }
        property.name = std::string(words.word[2]);
      }
      PlyElement& element = header.elements.back();
      if (element.find(property.name) >= 0) {
        return invalid_input(at_line(line_number) + "property " + quoted(property.name) +
                             " appears twice in element " + quoted(element.name));
      }
      element.properties.push_back(std::move(property));
      continue;
    }
    if (!contains_end_header(data + pos, size - pos)) {
      return invalid_input("the header has no 'end_header' line (line " +
                           std::to_string(line_number) + " " + quoted(keyword) +
                           " is not a header keyword)");
    }
    return invalid_input(at_line(line_number) + "unknown header keyword " + quoted(keyword));
  }
}

}  // namespace lodbake
