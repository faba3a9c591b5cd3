// Image file naming for written .gltf files (gltf_image_files.h).
#include "lib/dracoio/gltf_image_files.h"

#include <cstring>
#include <map>

namespace lodbake {
namespace dracoio {
namespace {

bool starts_with(const std::vector<uint8_t>& bytes, size_t offset, const char* magic,
                 size_t length) {
  return bytes.size() >= offset + length && std::memcmp(bytes.data() + offset, magic, length) == 0;
}

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

// "a/b.png" with `suffix` before the extension: "a/b_3.png".
std::string with_suffix(const std::string& name, const std::string& suffix) {
  const size_t slash = name.rfind('/');
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      dot == (slash == std::string::npos ? 0 : slash + 1)) {
    return name + suffix;
  }
  return name.substr(0, dot) + suffix + name.substr(dot);
}

}  // namespace

std::string image_mime_type(const std::string& declared, const std::vector<uint8_t>& bytes) {
  if (!declared.empty()) return declared;
  if (starts_with(bytes, 0, "\x89PNG\r\n\x1a\n", 8)) return "image/png";
  if (starts_with(bytes, 0, "\xff\xd8\xff", 3)) return "image/jpeg";
  if (starts_with(bytes, 0, "RIFF", 4) && starts_with(bytes, 8, "WEBP", 4)) return "image/webp";
  if (starts_with(bytes, 0, "\xabKTX 20\xbb\r\n\x1a\n", 12)) return "image/ktx2";
  return "";
}

std::string image_extension(const std::string& mime_type) {
  if (mime_type == "image/png") return "png";
  if (mime_type == "image/jpeg") return "jpg";
  if (mime_type == "image/webp") return "webp";
  if (mime_type == "image/ktx2") return "ktx2";
  return "bin";
}

std::string safe_relative_name(const std::string& uri) {
  if (uri.empty() || uri[0] == '/') return "";
  std::string out;
  size_t start = 0;
  while (start <= uri.size()) {
    size_t end = uri.find('/', start);
    if (end == std::string::npos) end = uri.size();
    const std::string segment = uri.substr(start, end - start);
    start = end + 1;
    if (segment.empty() || segment == ".") continue;
    if (segment == "..") return "";
    for (const char c : segment) {
      // ':' would read as a scheme or a drive letter, '\\' as a separator on
      // Windows; neither belongs in a name the writer creates.
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == ':' || c == '\\') return "";
    }
    if (!out.empty()) out += '/';
    out += segment;
  }
  return out;
}

std::string percent_encode(const std::string& name) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    const bool unreserved = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                            (c >= '0' && c <= '9') || c == '-' || c == '.' || c == '_' ||
                            c == '~' || c == '/';
    if (unreserved) {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

std::vector<std::string> image_file_names(const std::vector<SceneImage>& images,
                                          const std::string& gltf_name,
                                          const std::string& bin_name) {
  std::vector<std::string> names(images.size());
  // Lower-cased name -> the image written under it (-1: the .gltf or .bin).
  std::map<std::string, int64_t> taken = {{lower(gltf_name), -1}, {lower(bin_name), -1}};
  for (size_t i = 0; i < images.size(); ++i) {
    const SceneImage& image = images[i];
    if (image.missing) continue;
    std::string name = safe_relative_name(image.uri);
    if (name.empty()) {
      name = "image_" + std::to_string(i) + "." +
             image_extension(image_mime_type(image.mime_type, image.bytes));
    }
    auto it = taken.find(lower(name));
    if (it != taken.end() && it->second >= 0 && names[it->second] == name &&
        images[it->second].bytes == image.bytes) {
      names[i] = name;
      continue;
    }
    if (it != taken.end()) {
      name = with_suffix(name, "_" + std::to_string(i));
      // The suffixed name can only clash with an input name that happens to
      // look like it; count on until it is free.
      for (uint32_t n = 1; taken.count(lower(name)) != 0; ++n)
        name = with_suffix(name, "_" + std::to_string(n));
    }
    taken.emplace(lower(name), static_cast<int64_t>(i));
    names[i] = name;
  }
  return names;
}

}  // namespace dracoio
}  // namespace lodbake
