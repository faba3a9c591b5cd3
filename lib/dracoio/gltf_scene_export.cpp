// write_scene_glb() and write_scene_gltf() (lib/scene/scene_io.h): the JSON
// and buffer of gltf_scene_json.h in a GLB container, or as a .gltf with a
// .bin and the image files beside it. nlohmann's dump sorts object members,
// so equal scenes give equal bytes.
#include <new>
#include <string>

#include "lib/dracoio/gltf_image_files.h"
#include "lib/dracoio/gltf_scene_json.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kGlbVersion = 2;
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kGlbBinChunk = 0x004E4942;   // "BIN\0"

void append_u32(Bytes* out, uint64_t value) {
  for (int i = 0; i < 4; ++i)
    out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// Names and strings that are not valid UTF-8 (possible in a hand-built
// scene) are written with U+FFFD instead of throwing.
std::string dump(const nlohmann::json& root, int indent) {
  return root.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

Result<Bytes> write_glb_unchecked(const Scene& scene, SceneWriteReport* report) {
  LODBAKE_ASSIGN_OR_RETURN(dracoio::SceneGltf gltf,
                           dracoio::build_scene_gltf(scene, nullptr, report));
  if (!gltf.bin.empty()) gltf.root["buffers"] = {{{"byteLength", gltf.bin.size()}}};
  std::string json = dump(gltf.root, -1);
  json.append((4 - json.size() % 4) % 4, ' ');  // GLB pads the JSON chunk with spaces
  const uint64_t total =
      12 + 8 + uint64_t{json.size()} + (gltf.bin.empty() ? 0 : 8 + uint64_t{gltf.bin.size()});
  if (total > UINT32_MAX) return unsupported("the scene exceeds GLB's 4 GiB size limit");
  Bytes out;
  out.reserve(total);
  append_u32(&out, kGlbMagic);
  append_u32(&out, kGlbVersion);
  append_u32(&out, total);
  append_u32(&out, json.size());
  append_u32(&out, kGlbJsonChunk);
  out.insert(out.end(), json.begin(), json.end());
  if (!gltf.bin.empty()) {  // the buffer is already padded to 4 bytes with zeros
    append_u32(&out, gltf.bin.size());
    append_u32(&out, kGlbBinChunk);
    out.insert(out.end(), gltf.bin.begin(), gltf.bin.end());
  }
  return out;
}

Result<std::vector<SceneOutputFile>> write_gltf_unchecked(const Scene& scene,
                                                          const std::string& gltf_name,
                                                          SceneWriteReport* report) {
  const size_t slash = gltf_name.rfind('/');
  const std::string base = slash == std::string::npos ? gltf_name : gltf_name.substr(slash + 1);
  const size_t dot = base.rfind('.');
  std::string stem = dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
  if (stem.empty()) stem = "scene";
  const std::string bin_name = stem + ".bin";

  const std::vector<std::string> names = dracoio::image_file_names(scene.images, base, bin_name);
  std::vector<std::string> uris;
  for (const std::string& name : names)
    uris.push_back(dracoio::percent_encode(name));
  LODBAKE_ASSIGN_OR_RETURN(dracoio::SceneGltf gltf,
                           dracoio::build_scene_gltf(scene, &uris, report));
  if (!gltf.bin.empty()) {
    gltf.root["buffers"] = {
        {{"byteLength", gltf.bin.size()}, {"uri", dracoio::percent_encode(bin_name)}}};
  }
  std::vector<SceneOutputFile> files;
  const std::string json = dump(gltf.root, 2) + "\n";
  files.push_back({base, Bytes(json.begin(), json.end())});
  if (!gltf.bin.empty()) files.push_back({bin_name, std::move(gltf.bin)});
  for (size_t i = 0; i < scene.images.size(); ++i) {
    if (scene.images[i].missing) continue;
    bool written = false;  // images with the same name and bytes share one file
    for (size_t j = 0; j < i && !written; ++j)
      written = !scene.images[j].missing && names[j] == names[i];
    if (!written) files.push_back({names[i], scene.images[i].bytes});
  }
  return files;
}

}  // namespace

Result<Bytes> write_scene_glb(const Scene& scene, SceneWriteReport* report) {
  try {
    return write_glb_unchecked(scene, report);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while writing GLB");
  } catch (const std::exception& e) {
    return runtime_error(std::string("glTF encoding failed: ") + e.what());
  }
}

Result<std::vector<SceneOutputFile>> write_scene_gltf(const Scene& scene,
                                                      const std::string& gltf_name,
                                                      SceneWriteReport* report) {
  try {
    return write_gltf_unchecked(scene, gltf_name, report);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while writing glTF");
  } catch (const std::exception& e) {
    return runtime_error(std::string("glTF encoding failed: ") + e.what());
  }
}

}  // namespace lodbake
