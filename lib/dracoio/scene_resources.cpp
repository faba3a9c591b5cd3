// read_resource(): the files a glTF (or OBJ) asset names, confined to the
// asset's folder. glTF 2.0 ("URIs") allows relative references, data: URIs
// and, in principle, any scheme; a tool run on someone else's asset must not
// read /etc/passwd or fetch from the network because the asset says so.
// Choices:
// - Percent-escapes are decoded first, so "%2e%2e/x" is "../x" and refused.
// - Confinement is lexical: "." and ".." are resolved in the decoded path,
//   and a path that climbs above the folder at any point is refused (even if
//   it comes back, "a/../../folder/x"); symbolic links inside the folder
//   are followed as the file system has them.
// - Any scheme other than data: is refused, with or without allow_outside:
//   lodbake reads files, not URLs. A single letter before ':' is a Windows
//   drive, i.e. an absolute path.
#include <string>
#include <vector>

#include "lib/dracoio/gltf_document.h"
#include "lib/dracoio/gltf_uri.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace dracoio {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The scheme of `uri` ("http" for "http://x"), or empty for a relative
// reference: RFC 3986 scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ).
std::string scheme_of(const std::string& uri) {
  const size_t colon = uri.find(':');
  if (colon == std::string::npos || colon == 0) return std::string();
  for (size_t i = 0; i < colon; ++i) {
    const char c = uri[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    const bool other = (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
    if (!(alpha || (i > 0 && other))) return std::string();
  }
  return uri.substr(0, colon);
}

std::string shown(const std::string& uri) {
  return "'" + uri.substr(0, 200) + "'";
}

}  // namespace

Result<std::string> percent_decode(const std::string& uri) {
  std::string out;
  out.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out.push_back(uri[i]);
      continue;
    }
    const int hi = i + 2 < uri.size() ? hex_value(uri[i + 1]) : -1;
    const int lo = i + 2 < uri.size() ? hex_value(uri[i + 2]) : -1;
    if (hi < 0 || lo < 0) {
      return invalid_input("URI " + shown(uri) + " has a malformed %-escape at offset " +
                           std::to_string(i));
    }
    const char c = static_cast<char>(hi * 16 + lo);
    if (c == '\0') return invalid_input("URI " + shown(uri) + " decodes to a NUL byte");
    out.push_back(c);
    i += 2;
  }
  return out;
}

}  // namespace dracoio

Result<Bytes> read_resource(const SceneResources& resources, const std::string& uri,
                            std::string* resolved_path) {
  if (uri.compare(0, 5, "data:") == 0) return dracoio::decode_data_uri(uri, "URI");
  const std::string scheme = dracoio::scheme_of(uri);
  if (scheme.size() > 1) {
    return unsupported("URI " + dracoio::shown(uri) + " uses the scheme '" + scheme.substr(0, 40) +
                       ":'; lodbake reads only relative file names and data: URIs");
  }
  LODBAKE_ASSIGN_OR_RETURN(const std::string name, dracoio::percent_decode(uri));
  if (resources.folder.empty()) {
    return unsupported("the asset is read from memory; external file " + dracoio::shown(name) +
                       " cannot be resolved");
  }
  const bool absolute = !name.empty() && (name[0] == '/' || name[0] == '\\' || scheme.size() == 1);
  if (absolute && !resources.allow_outside) {
    return unsupported("URI " + dracoio::shown(uri) +
                       " is an absolute path, outside the asset's folder (--allow-outside "
                       "reads it)");
  }
  // Resolve "." and ".." lexically: ".." below the folder's own level
  // leaves it; the path read is the normalized one, so "sub/../x" needs no
  // folder "sub".
  std::vector<std::string> kept;
  size_t begin = absolute && scheme.empty() ? 1 : 0;
  while (begin <= name.size()) {
    size_t end = name.find_first_of("/\\", begin);
    if (end == std::string::npos) end = name.size();
    const std::string segment = name.substr(begin, end - begin);
    if (segment == "..") {
      if (!kept.empty() && kept.back() != "..") {
        kept.pop_back();
      } else if (!resources.allow_outside && !absolute) {
        return unsupported("URI " + dracoio::shown(uri) +
                           " leaves the asset's folder through '..' (--allow-outside reads it)");
      } else if (!absolute) {
        kept.push_back(segment);
      }
    } else if (!segment.empty() && segment != ".") {
      kept.push_back(segment);
    }
    begin = end + 1;
  }
  std::string relative;
  for (const std::string& segment : kept)
    relative += (relative.empty() ? "" : "/") + segment;
  if (relative.empty()) return invalid_input("URI " + dracoio::shown(uri) + " names no file");
  const std::string path = absolute && scheme.empty() ? "/" + relative
                           : absolute                 ? name
                                                      : resources.folder + "/" + relative;
  if (resolved_path != nullptr) *resolved_path = path;
  auto bytes = read_file(path);
  if (resources.on_read) resources.on_read(path, bytes.is_ok() ? &bytes.value() : nullptr);
  if (!bytes.is_ok()) {
    return Status(bytes.status().kind(),
                  "file " + dracoio::shown(name) + " cannot be read: " + bytes.status().message());
  }
  return bytes;
}

}  // namespace lodbake
