#include "tools/common/asset_report.h"

#include <iostream>

#include "formats/container/container_layout.h"
#include "formats/sections/open_container.h"
#include "lib/core/sha256.h"
#include "lib/ingest/container_mesh.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {

MetaInput asset_meta_input(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    Result<OpenedContainer> opened = open_container(bytes);
    if (opened.is_ok())
      if (std::optional<MetaInput> input = container_meta_input(opened.value())) return *input;
  }
  const size_t slash = path.find_last_of('/');
  return MetaInput{to_valid_utf8(slash == std::string::npos ? path : path.substr(slash + 1)),
                   sha256_hex(bytes.data(), bytes.size()), bytes.size()};
}

int print_asset_build(const Tool& tool, const char* schema, const std::string& input,
                      const std::string& output, const AssetBuild& built) {
  if (tool.json()) {
    tool.print_json({{"schema", schema},
                     {"input", input},
                     {"asset", true},
                     {"output", output},
                     {"bytes", built.file.size()},
                     {"groups", built.groups}});
    return 0;
  }
  std::cout << "input       " << input << ": an asset, " << built.groups.size()
            << " meshes with triangles, each built once in its own group\n";
  for (const nlohmann::json& g : built.groups) {
    std::cout << "group " << g["group"].get<uint64_t>() << "     mesh " << g["mesh"].get<uint64_t>()
              << ", " << g["triangles"].get<uint64_t>() << " triangles"
              << (g["repaired"].get<bool>() ? " (repaired)" : "") << ": " << g["report"].dump()
              << "\n";
  }
  std::cout << "wrote       " << output << ": " << built.file.size() << " bytes\n";
  return 0;
}

}  // namespace lodbake::cli
