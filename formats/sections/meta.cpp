// META section: one JSON object (RFC 8259, UTF-8) with sorted keys and no
// insignificant whitespace, via nlohmann::json, whose objects are ordered
// maps and whose dump() of numbers is shortest-round-trip; that makes the
// bytes deterministic.
//
// Hostile input: nlohmann's parser is iterative, but dump() and our own
// walks would recurse per nesting level, so the depth is bounded on the raw
// bytes (string-aware bracket count) before parsing, and the size is bounded
// before that.
#include "formats/sections/meta.h"

#include <cmath>
#include <new>
#include <utility>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/string_format.h"
#include "formats/support/version.h"

namespace lodbake {
namespace {

using Json = nlohmann::json;

Status bad_meta(const std::string& detail) {
  return malformed_section(kMetaTag, detail);
}

// Deepest array/object nesting in JSON text, ignoring brackets inside
// strings; -1 when it exceeds `limit` (stops scanning there).
int max_text_depth(const uint8_t* data, size_t size, int limit) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t c = data[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character cannot end the string
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return -1;
      if (depth > deepest) deepest = depth;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

bool is_sha256_hex(const std::string& s) {
  if (s.size() != 64) return false;
  for (char c : s) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

// Iterative walk (explicit stack): depth and finiteness of every number.
Status check_json_value(const Json& root, const char* what) {
  std::vector<std::pair<const Json*, int>> stack = {{&root, 1}};
  while (!stack.empty()) {
    const auto [value, depth] = stack.back();
    stack.pop_back();
    if (value->is_number_float() && !std::isfinite(value->get<double>())) {
      return invalid_input(string_printf("META %s holds a non-finite number", what));
    }
    if (value->is_structured()) {
      if (depth > kMaxMetaDepth) {
        return invalid_input(
            string_printf("META %s nests deeper than %d levels", what, kMaxMetaDepth));
      }
      for (const Json& child : *value)
        stack.emplace_back(&child, depth + 1);
    }
  }
  return Status::ok();
}

const char* const kStandardKeys[] = {"tool", "version", "options", "input", "counts"};

Status parse_document(const uint8_t* data, size_t size, Json* out) {
  if (size > kMaxMetaBytes) {
    return bad_meta(string_printf("%zu bytes of JSON, at most %zu allowed", size, kMaxMetaBytes));
  }
  if (max_text_depth(data, size, kMaxMetaDepth) < 0) {
    return bad_meta(string_printf("JSON nests deeper than %d levels", kMaxMetaDepth));
  }
  try {
    *out = Json::parse(data, data + size);
  } catch (const Json::parse_error& e) {
    return bad_meta(string_printf("not valid JSON (error at byte %zu)", e.byte));
  } catch (const Json::out_of_range&) {
    return bad_meta("not valid JSON (a number is out of range)");
  } catch (const Json::exception&) {
    return bad_meta("not valid JSON");
  }
  if (!out->is_object()) {
    return bad_meta(std::string("JSON is ") + out->type_name() + ", expected an object");
  }
  return Status::ok();
}

Status meta_from_json(const Json& doc, MetaSection* meta) {
  const auto tool = doc.find("tool");
  if (tool == doc.end() || !tool->is_string()) return bad_meta("key \"tool\" must be a string");
  const auto version = doc.find("version");
  if (version == doc.end() || !version->is_string()) {
    return bad_meta("key \"version\" must be a string");
  }
  meta->tool = tool->get<std::string>();
  meta->version = version->get<std::string>();
  if (const auto options = doc.find("options"); options != doc.end()) {
    if (!options->is_object()) return bad_meta("key \"options\" must be an object");
    meta->options = *options;
  }
  if (const auto input = doc.find("input"); input != doc.end()) {
    if (!input->is_object()) return bad_meta("key \"input\" must be an object");
    const auto file = input->find("file");
    const auto sha = input->find("sha256");
    const auto bytes = input->find("bytes");
    if (file == input->end() || !file->is_string()) {
      return bad_meta("key \"input.file\" must be a string");
    }
    if (sha == input->end() || !sha->is_string() || !is_sha256_hex(sha->get<std::string>())) {
      return bad_meta("key \"input.sha256\" must be 64 lower-case hex digits");
    }
    if (bytes == input->end() || !bytes->is_number_unsigned()) {
      return bad_meta("key \"input.bytes\" must be an unsigned integer");
    }
    meta->input =
        MetaInput{file->get<std::string>(), sha->get<std::string>(), bytes->get<uint64_t>()};
  }
  if (const auto counts = doc.find("counts"); counts != doc.end()) {
    if (!counts->is_object()) return bad_meta("key \"counts\" must be an object");
    for (auto it = counts->begin(); it != counts->end(); ++it) {
      if (!it.value().is_number_unsigned()) {
        return bad_meta("count \"" + it.key() + "\" must be an unsigned integer");
      }
      meta->counts[it.key()] = it.value().get<uint64_t>();
    }
  }
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    bool standard = false;
    for (const char* key : kStandardKeys)
      standard = standard || it.key() == key;
    if (!standard) meta->extra[it.key()] = it.value();
  }
  return Status::ok();
}

}  // namespace

MetaSection make_meta(std::string tool) {
  MetaSection meta;
  meta.tool = std::move(tool);
  meta.version = kLodbakeVersion;
  return meta;
}

Json meta_to_json(const MetaSection& meta) {
  Json doc = meta.extra.is_object() ? meta.extra : Json::object();
  doc["tool"] = meta.tool;
  doc["version"] = meta.version;
  doc["options"] = meta.options;
  if (meta.input) {
    doc["input"] = Json{{"file", meta.input->file_name},
                        {"sha256", meta.input->sha256_hex},
                        {"bytes", meta.input->bytes}};
  }
  Json counts = Json::object();
  for (const auto& [name, value] : meta.counts)
    counts[name] = value;
  doc["counts"] = std::move(counts);
  return doc;
}

Result<Bytes> encode_meta(const MetaSection& meta) {
  if (meta.tool.empty()) return invalid_input("META tool name is empty");
  if (meta.version.empty()) return invalid_input("META version is empty");
  if (!meta.options.is_object()) return invalid_input("META options must be a JSON object");
  if (!meta.extra.is_object()) return invalid_input("META extra keys must be a JSON object");
  for (const char* key : kStandardKeys) {
    if (meta.extra.contains(key)) {
      return invalid_input(std::string("META extra keys repeat the standard key \"") + key + "\"");
    }
  }
  if (meta.input && !is_sha256_hex(meta.input->sha256_hex)) {
    return invalid_input("META input sha256 must be 64 lower-case hex digits");
  }
  try {
    const Json doc = meta_to_json(meta);
    LODBAKE_RETURN_IF_ERROR(check_json_value(doc, "document"));
    // strict: invalid UTF-8 in a string throws instead of being replaced.
    const std::string text = doc.dump(-1, ' ', false, Json::error_handler_t::strict);
    if (text.size() > kMaxMetaBytes) {
      return invalid_input(string_printf("META would be %zu bytes, at most %zu allowed",
                                         text.size(), kMaxMetaBytes));
    }
    return Bytes(text.begin(), text.end());
  } catch (const Json::type_error&) {
    return invalid_input("META holds a string that is not valid UTF-8");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding META");
  }
}

Result<nlohmann::json> decode_meta_json(const uint8_t* data, size_t size) {
  try {
    Json doc;
    LODBAKE_RETURN_IF_ERROR(parse_document(data, size, &doc));
    MetaSection checked;
    LODBAKE_RETURN_IF_ERROR(meta_from_json(doc, &checked));
    return doc;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding META");
  }
}

Result<MetaSection> decode_meta(const uint8_t* data, size_t size) {
  try {
    Json doc;
    LODBAKE_RETURN_IF_ERROR(parse_document(data, size, &doc));
    MetaSection meta;
    LODBAKE_RETURN_IF_ERROR(meta_from_json(doc, &meta));
    return meta;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding META");
  }
}

}  // namespace lodbake
