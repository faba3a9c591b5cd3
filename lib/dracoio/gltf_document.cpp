// glTF 2.0 container and buffer loading (Khronos glTF 2.0 specification,
// sections "GLB File Format Specification" and "Buffers and Buffer Views").
// Choices where the specification leaves room or readers differ:
// - The GLB length field must equal the data size: a shorter field means
//   trailing bytes, a longer one a truncated file; both are errors.
// - Chunks after BIN are skipped, as the specification asks for unknown
//   chunk types; a second JSON or BIN chunk is an error.
// - A JSON text may start with a UTF-8 byte order mark (the specification
//   forbids it, but some exporters write one); it is skipped.
// - JSON nesting is bounded (kMaxJsonDepth) by a scan before parsing.
// - Buffers: byteLength may be smaller than the data (the rest is ignored),
//   never larger. Only base64 data: URIs are embedded; any other URI names a
//   file, read through read_resource() (refused when reading from memory).
// - A buffer without uri (other than a GLB's buffer 0) is accepted only as
//   an EXT_meshopt_compression fallback; it holds no bytes, so a bufferView
//   into it reads only when the extension decodes that view.
#include "lib/dracoio/gltf_document.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "formats/support/byte_reader.h"
#include "lib/dracoio/gltf_meshopt.h"

namespace lodbake {
namespace dracoio {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr uint64_t kMinDecodeBudget = uint64_t{1} << 26;
constexpr uint64_t kDecodeBudgetPerByte = 64;

std::string str(uint64_t v) {
  return std::to_string(v);
}

std::string plural(const std::string& what) {
  return what + (!what.empty() && what.back() == 'h' ? "es" : "s");
}

struct Container {
  const uint8_t* json = nullptr;
  size_t json_size = 0;
  const uint8_t* bin = nullptr;
  size_t bin_size = 0;
  bool has_bin = false;
};

Status read_glb(const uint8_t* data, size_t size, Container* out) {
  ByteReader reader(data, size);
  uint32_t magic = 0, version = 0, length = 0;
  if (!reader.read(&magic) || !reader.read(&version) || !reader.read(&length)) {
    return invalid_input("GLB header needs 12 bytes, the data has " + str(size));
  }
  if (version != 2) {
    return unsupported("GLB version " + str(version) + " is not supported (only 2, glTF 2.0)");
  }
  if (length > size) {
    return invalid_input("GLB header says " + str(length) + " bytes, the data ends at byte " +
                         str(size));
  }
  if (length < size) {
    return invalid_input("GLB header says " + str(length) + " bytes, " + str(size - length) +
                         " trailing bytes follow");
  }
  bool seen_json = false;
  while (!reader.at_end()) {
    const size_t chunk_start = reader.position();
    uint32_t chunk_length = 0, chunk_type = 0;
    if (!reader.read(&chunk_length) || !reader.read(&chunk_type)) {
      return invalid_input("GLB chunk header at byte " + str(chunk_start) + " is truncated");
    }
    if (chunk_length > reader.remaining()) {
      return invalid_input("GLB chunk at byte " + str(chunk_start) + " declares " +
                           str(chunk_length) + " bytes, only " + str(reader.remaining()) +
                           " remain");
    }
    const uint8_t* body = reader.current();
    reader.skip(chunk_length);
    if (!seen_json) {
      if (chunk_type != kChunkJson) {
        return invalid_input("the first GLB chunk is not JSON");
      }
      seen_json = true;
      out->json = body;
      out->json_size = chunk_length;
    } else if (chunk_type == kChunkJson) {
      return invalid_input("GLB has a second JSON chunk at byte " + str(chunk_start));
    } else if (chunk_type == kChunkBin) {
      if (out->has_bin)
        return invalid_input("GLB has a second BIN chunk at byte " + str(chunk_start));
      out->has_bin = true;
      out->bin = body;
      out->bin_size = chunk_length;
    }
  }
  if (!seen_json) return invalid_input("GLB has no JSON chunk");
  return Status::ok();
}

// Rejects nesting deeper than kMaxJsonDepth before the parser sees the text.
Status check_json_depth(const uint8_t* data, size_t size) {
  size_t depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t c = data[i];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        return invalid_input("JSON nesting deeper than " + str(kMaxJsonDepth) + " levels at byte " +
                             str(i));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return Status::ok();
}

int base64_value(uint8_t c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

Result<Bytes> decode_base64(const std::string& text, size_t begin, const std::string& where) {
  size_t end = text.size();
  while (end > begin && text[end - 1] == '=' && text.size() - end < 2)
    --end;
  Bytes out;
  out.reserve((end - begin) / 4 * 3 + 3);
  uint32_t acc = 0;
  int bits = 0;
  for (size_t i = begin; i < end; ++i) {
    const int v = base64_value(static_cast<uint8_t>(text[i]));
    if (v < 0) {
      return invalid_input(where + ": invalid base64 character at offset " + str(i) +
                           " of its data: URI");
    }
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>((acc >> bits) & 0xFF));
    }
  }
  if (bits >= 6) return invalid_input(where + ": base64 data: URI has a dangling character");
  return out;
}

bool is_meshopt_fallback(const Json& buffer) {
  const auto ext = buffer.find("extensions");
  if (ext == buffer.end() || !ext->is_object()) return false;
  const auto meshopt = ext->find("EXT_meshopt_compression");
  if (meshopt == ext->end() || !meshopt->is_object()) return false;
  const auto fallback = meshopt->find("fallback");
  return fallback != meshopt->end() && fallback->is_boolean() && fallback->get<bool>();
}

Status load_buffers(const Container& container, const SceneResources& resources,
                    GltfDocument* doc) {
  LODBAKE_ASSIGN_OR_RETURN(const Json* buffers, member_array(doc->root, "buffers", "glTF"));
  if (buffers == nullptr) return Status::ok();
  doc->buffers.reserve(buffers->size());
  doc->decoded.reserve(buffers->size());
  for (size_t i = 0; i < buffers->size(); ++i) {
    const std::string where = "buffer " + str(i);
    const Json& buffer = (*buffers)[i];
    if (!buffer.is_object()) return invalid_input(where + " is not a JSON object");
    LODBAKE_ASSIGN_OR_RETURN(
        const uint64_t byte_length,
        member_uint(buffer, "byteLength", UINT64_MAX, std::numeric_limits<size_t>::max(), where));
    if (byte_length == UINT64_MAX) return invalid_input(where + " has no byteLength");
    const auto uri = buffer.find("uri");
    ByteSpan span;
    if (uri == buffer.end()) {
      if (doc->binary && i == 0) {
        if (!container.has_bin) {
          return invalid_input(where + " refers to a BIN chunk the GLB lacks");
        }
        if (byte_length > container.bin_size) {
          return invalid_input(where + " declares " + str(byte_length) +
                               " bytes, the GLB BIN chunk holds " + str(container.bin_size));
        }
        span.data = container.bin;
        span.size = static_cast<size_t>(byte_length);
      } else if (!is_meshopt_fallback(buffer)) {
        return invalid_input(where +
                             " has no uri (only buffer 0 of a GLB may use the BIN chunk, and "
                             "an EXT_meshopt_compression fallback buffer may have no data)");
      }
      doc->buffers.push_back(span);
      continue;
    }
    if (!uri->is_string()) return invalid_input(where + ": 'uri' is not a string");
    const std::string& text = uri->get_ref<const std::string&>();
    Bytes bytes;
    if (text.compare(0, 5, "data:") == 0) {
      LODBAKE_ASSIGN_OR_RETURN(bytes, decode_data_uri(text, where));
    } else {
      auto read = read_resource(resources, text);
      if (!read.is_ok())
        return Status(read.status().kind(), where + ": " + read.status().message());
      bytes = std::move(read).value();
    }
    if (byte_length > bytes.size()) {
      return invalid_input(where + " declares " + str(byte_length) + " bytes, its " +
                           (text.compare(0, 5, "data:") == 0 ? "data: URI" : "file") + " holds " +
                           str(bytes.size()));
    }
    doc->decoded.push_back(std::move(bytes));
    // Moving a vector keeps its heap block, so this pointer stays valid.
    span.data = doc->decoded.back().data();
    span.size = static_cast<size_t>(byte_length);
    doc->buffers.push_back(span);
  }
  return Status::ok();
}

Status check_asset(const Json& root) {
  LODBAKE_ASSIGN_OR_RETURN(const Json* asset, member_object(root, "asset", "glTF"));
  if (asset == nullptr) return invalid_input("glTF has no 'asset' object");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) {
    return invalid_input("glTF asset has no 'version' string");
  }
  const std::string& v = version->get_ref<const std::string&>();
  if (v.compare(0, 2, "2.") != 0) {
    return unsupported("glTF version '" + v.substr(0, 20) + "' is not supported (only 2.x)");
  }
  const auto min_version = asset->find("minVersion");
  if (min_version != asset->end() && min_version->is_string() &&
      min_version->get_ref<const std::string&>() != "2.0") {
    return unsupported("glTF minVersion '" + min_version->get<std::string>().substr(0, 20) +
                       "' is newer than 2.0");
  }
  return Status::ok();
}

bool integral(const Json& value, int64_t* out) {
  if (value.is_number_unsigned()) {
    const uint64_t v = value.get<uint64_t>();
    if (v > static_cast<uint64_t>(INT64_MAX)) return false;
    *out = static_cast<int64_t>(v);
    return true;
  }
  if (value.is_number_integer()) {
    *out = value.get<int64_t>();
    return true;
  }
  if (value.is_number_float()) {
    // Some exporters write counts as 3.0.
    const double d = value.get<double>();
    if (!(std::fabs(d) < 9.0e15) || d != std::floor(d)) return false;
    *out = static_cast<int64_t>(d);
    return true;
  }
  return false;
}

}  // namespace

Status DecodeBudget::charge(uint64_t bytes, const std::string& what) {
  if (bytes > limit_ - used_) {
    return invalid_input(what + " would decode more than " + str(limit_) +
                         " bytes in all, the limit for an input of this size");
  }
  used_ += bytes;
  return Status::ok();
}

Result<Bytes> decode_data_uri(const std::string& text, const std::string& where) {
  const size_t comma = text.find(',');
  if (text.compare(0, 5, "data:") != 0 || comma == std::string::npos || comma < 12 ||
      text.compare(comma - 7, 7, ";base64") != 0) {
    return unsupported(where + ": only base64 data: URIs are supported");
  }
  return decode_base64(text, comma + 1, where);
}

Result<GltfDocument> load_gltf_document(const uint8_t* data, size_t size,
                                        const SceneResources& resources) {
  GltfDocument doc;
  Container container;
  if (size >= 4) {
    uint32_t magic = 0;
    std::memcpy(&magic, data, 4);
    doc.binary = magic == kGlbMagic;
  }
  if (doc.binary) {
    LODBAKE_RETURN_IF_ERROR(read_glb(data, size, &container));
  } else {
    container.json = data;
    container.json_size = size;
    if (size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF) {
      container.json += 3;
      container.json_size -= 3;
    }
  }
  LODBAKE_RETURN_IF_ERROR(check_json_depth(container.json, container.json_size));
  try {
    doc.root = Json::parse(container.json, container.json + container.json_size);
  } catch (const Json::parse_error& e) {
    return invalid_input(std::string(doc.binary ? "GLB JSON chunk" : "glTF JSON") +
                         ": syntax error at byte " + str(e.byte));
  }
  if (!doc.root.is_object()) return invalid_input("glTF JSON is not an object");
  LODBAKE_RETURN_IF_ERROR(check_asset(doc.root));
  LODBAKE_RETURN_IF_ERROR(load_buffers(container, resources, &doc));
  uint64_t input_bytes = size;
  for (const Bytes& b : doc.decoded)
    input_bytes += b.size();
  doc.budget = DecodeBudget(std::max(kMinDecodeBudget, kDecodeBudgetPerByte * input_bytes));
  LODBAKE_RETURN_IF_ERROR(decode_meshopt_views(&doc));
  return doc;
}

Result<const Json*> member_array(const Json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return static_cast<const Json*>(nullptr);
  if (!it->is_array()) return invalid_input(where + ": '" + key + "' is not an array");
  return &*it;
}

Result<const Json*> member_object(const Json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return static_cast<const Json*>(nullptr);
  if (!it->is_object()) return invalid_input(where + ": '" + key + "' is not an object");
  return &*it;
}

Result<int64_t> as_index(const Json& value, size_t limit, const char* what,
                         const std::string& where) {
  int64_t index = 0;
  if (!integral(value, &index) || index < 0) {
    return invalid_input(where + ": " + what + " index is not a non-negative integer");
  }
  if (static_cast<uint64_t>(index) >= limit) {
    return invalid_input(where + ": " + what + " " + str(static_cast<uint64_t>(index)) +
                         " out of range (" + str(limit) + " " + plural(what) + ")");
  }
  return index;
}

Result<int64_t> member_index(const Json& object, const char* key, size_t limit, const char* what,
                             const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return int64_t{-1};
  return as_index(*it, limit, what, where);
}

Result<uint64_t> member_uint(const Json& object, const char* key, uint64_t default_value,
                             uint64_t max, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return default_value;
  int64_t value = 0;
  if (!integral(*it, &value) || value < 0) {
    return invalid_input(where + ": '" + key + "' is not a non-negative integer");
  }
  if (static_cast<uint64_t>(value) > max) {
    return invalid_input(where + ": '" + key + "' " + str(static_cast<uint64_t>(value)) +
                         " exceeds " + str(max));
  }
  return static_cast<uint64_t>(value);
}

Result<std::vector<double>> member_numbers(const Json& object, const char* key, size_t count,
                                           const std::string& where) {
  std::vector<double> numbers;
  const auto it = object.find(key);
  if (it == object.end()) return numbers;
  if (!it->is_array() || it->size() != count) {
    return invalid_input(where + ": '" + key + "' is not an array of " + str(count) + " numbers");
  }
  for (const Json& v : *it) {
    if (!v.is_number()) {
      return invalid_input(where + ": '" + key + "' is not an array of " + str(count) + " numbers");
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) return invalid_input(where + ": '" + key + "' has a non-finite value");
    numbers.push_back(d);
  }
  return numbers;
}

size_t top_level_count(const Json& root, const char* key) {
  const auto it = root.find(key);
  return it != root.end() && it->is_array() ? it->size() : 0;
}

}  // namespace dracoio
}  // namespace lodbake
