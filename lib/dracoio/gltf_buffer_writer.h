// Internal to lib/dracoio: lays out the one glTF buffer a scene writer
// writes, with one bufferView per accessor or image, each starting on a
// 4-byte boundary. Vertex attribute views carry a byteStride that is a
// multiple of 4 (elements padded with zeros: a VEC3 UNSIGNED_BYTE element
// takes 4 bytes); matrix columns of 1- and 2-byte components are padded to 4
// bytes as glTF requires; index views are tightly packed in the smallest
// unsigned type whose primitive-restart value no index reaches.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/scene/scene.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {
namespace dracoio {

class GltfBufferWriter {
 public:
  enum class Use { kVertices, kOther };

  // Appends `data` as an accessor (and its bufferView); `bounds` writes min
  // and max (required on POSITION and animation inputs), computed in the
  // component type. Fails with kInvalidInput, naming `where`, when the
  // accessor is empty or its bytes do not match its count.
  Result<uint32_t> add_accessor(const AccessorData& data, Use use, bool bounds,
                                const std::string& where);
  // Appends an index accessor; every index must be below `vertex_count`.
  Result<uint32_t> add_indices(const std::vector<uint32_t>& indices, uint32_t vertex_count,
                               const std::string& where);
  // Appends raw bytes (an image) as a bufferView without stride or target.
  Result<uint32_t> add_view(const std::vector<uint8_t>& bytes, const std::string& where);

  const nlohmann::json& accessors() const { return accessors_; }
  const nlohmann::json& buffer_views() const { return views_; }
  // The buffer, its length a multiple of 4.
  const Bytes& bytes() const { return bin_; }

 private:
  uint32_t begin_view();
  void end_view(size_t start, uint32_t stride, int target);

  nlohmann::json accessors_ = nlohmann::json::array();
  nlohmann::json views_ = nlohmann::json::array();
  Bytes bin_;
};

}  // namespace dracoio
}  // namespace lodbake
