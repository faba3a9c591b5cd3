#include "lib/ingest/meta_input.h"

#include <nlohmann/json.hpp>
#include <optional>

#include "formats/container/container_layout.h"
#include "formats/sections/open_container.h"
#include "lib/core/sha256.h"
#include "lib/ingest/container_mesh.h"

namespace lodbake {
namespace {

std::string base_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

std::string to_valid_utf8(const std::string& text) {
  // nlohmann's replace handler implements the substitution; reading the
  // dumped string back undoes the JSON escaping.
  std::string quoted =
      nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return nlohmann::json::parse(quoted).get<std::string>();
}

MetaInput meta_input(const std::string& path, const LoadedMesh& loaded) {
  if (loaded.original_input) return *loaded.original_input;
  return MetaInput{to_valid_utf8(base_name(path)), loaded.sha256, loaded.file_bytes};
}

MetaInput asset_meta_input(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    Result<OpenedContainer> opened = open_container(bytes);
    if (opened.is_ok())
      if (std::optional<MetaInput> input = container_meta_input(opened.value())) return *input;
  }
  return MetaInput{to_valid_utf8(base_name(path)), sha256_hex(bytes.data(), bytes.size()),
                   bytes.size()};
}

}  // namespace lodbake
