// Internal to lib/dracoio: a glTF 2.0 asset loaded from memory, with its
// container checked (GLB header and chunks, JSON nesting), every buffer
// resolved to bytes (GLB BIN chunk, base64 data: URI or a file read through
// SceneResources) and EXT_meshopt_compression bufferViews decoded, plus typed JSON
// accessors that turn a wrong type or an out-of-range index into a one-line
// Status naming the object ("node 3: 'mesh' 7 out of range (2 meshes)").
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <map>
#include <new>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace dracoio {

using Json = nlohmann::json;

struct ByteSpan {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

// A cap on the bytes a reader may produce from one asset (decoded
// compression, densified accessors, zero-filled accessors without data), so
// that a small file cannot ask for gigabytes.
class DecodeBudget {
 public:
  explicit DecodeBudget(uint64_t limit = 0) : limit_(limit) {}
  // Takes `bytes` from the budget, or fails naming `what`.
  Status charge(uint64_t bytes, const std::string& what);
  uint64_t limit() const { return limit_; }

 private:
  uint64_t limit_;
  uint64_t used_ = 0;
};

struct GltfDocument {
  Json root;                      // the top-level JSON object
  bool binary = false;            // read from a GLB container
  std::vector<ByteSpan> buffers;  // buffers[i].size == buffers[i].byteLength
  std::vector<Bytes> decoded;     // storage behind data: URI and external buffers
  // EXT_meshopt_compression bufferViews, decoded: buffer_view_bytes() hands
  // these out instead of the view's (fallback) buffer range.
  std::map<int64_t, Bytes> decoded_views;
  // max(2^26, 64 x (input + buffer bytes)); meshopt decoding has drawn on it.
  DecodeBudget budget;
};

// Deepest JSON nesting accepted; real assets stay far below it, and the bound
// keeps every JSON walk (ours and the library's) shallow.
constexpr size_t kMaxJsonDepth = 64;

// Parses a .gltf (JSON text) or .glb (binary container) held in memory.
// External buffer URIs are read through `resources` (read_resource(): with
// the default, memory only, they are refused with kUnsupported). A buffer
// with no uri that EXT_meshopt_compression marks as a fallback has no bytes;
// the compressed bufferViews that use it are decoded here.
Result<GltfDocument> load_gltf_document(const uint8_t* data, size_t size,
                                        const SceneResources& resources = SceneResources());

// The bytes of a base64 data: URI, `where` naming its owner.
Result<Bytes> decode_data_uri(const std::string& uri, const std::string& where);

// Members of `object` named `key`. Absent members give an empty array / the
// default; a member of the wrong type or out of range is an error naming
// `where` and `key`.
Result<const Json*> member_array(const Json& object, const char* key, const std::string& where);
Result<const Json*> member_object(const Json& object, const char* key, const std::string& where);
// An index into an array of `limit` elements called `what`; -1 when absent.
Result<int64_t> member_index(const Json& object, const char* key, size_t limit, const char* what,
                             const std::string& where);
// A non-negative integer no larger than `max`; `default_value` when absent.
Result<uint64_t> member_uint(const Json& object, const char* key, uint64_t default_value,
                             uint64_t max, const std::string& where);
// Exactly `count` finite numbers; empty when absent.
Result<std::vector<double>> member_numbers(const Json& object, const char* key, size_t count,
                                           const std::string& where);
// The value of an array element or member as an index (integral number).
Result<int64_t> as_index(const Json& value, size_t limit, const char* what,
                         const std::string& where);

// Runs a reader, turning the exceptions its bounded checks do not foresee
// (out of memory, a library exception) into one-line statuses.
template <typename T, typename Read>
Result<T> guard_exceptions(Read&& read) {
  try {
    return read();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading glTF");
  } catch (const std::exception& e) {
    std::string what = e.what();
    if (what.size() > 200) what.resize(200);
    return invalid_input("glTF could not be read: " + what);
  }
}

// The length of the named top-level array (0 when absent or not an array).
size_t top_level_count(const Json& root, const char* key);

}  // namespace dracoio
}  // namespace lodbake
