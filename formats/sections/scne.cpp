#include "formats/sections/scne.h"

#include <string>

#include <nlohmann/json.hpp>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kGlbVersion = 2;

Status bad(const std::string& detail) {
  return malformed_section(kScneTag, detail);
}

std::string str(uint64_t v) {
  return std::to_string(v);
}

// The rules both directions share.
Status check_map(const std::vector<SceneMeshGroup>& meshes) {
  std::vector<uint32_t> groups;
  for (size_t i = 0; i < meshes.size(); ++i) {
    if (i > 0 && meshes[i].mesh <= meshes[i - 1].mesh)
      return bad("mesh " + str(meshes[i].mesh) + " is listed after mesh " +
                 str(meshes[i - 1].mesh) + " (meshes must increase)");
    for (uint32_t g : groups)
      if (g == meshes[i].group) return bad("group " + str(g) + " is given to two meshes");
    groups.push_back(meshes[i].group);
  }
  return Status::ok();
}

}  // namespace

Result<Bytes> encode_scne(const SceneSection& section) {
  Status checked = check_map(section.meshes);
  if (!checked.is_ok()) return invalid_input("cannot encode SCNE: " + checked.message());
  nlohmann::json meshes = nlohmann::json::array();
  for (const SceneMeshGroup& m : section.meshes)
    meshes.push_back({{"mesh", m.mesh}, {"group", m.group}, {"triangles", m.triangles}});
  nlohmann::json map_json = {{"meshes", meshes}};
  if (!section.image_uris.empty()) map_json["image_uris"] = section.image_uris;
  const std::string map = map_json.dump();
  Bytes out(4);
  const uint32_t n = static_cast<uint32_t>(map.size());
  for (int i = 0; i < 4; ++i)
    out[i] = static_cast<uint8_t>(n >> (8 * i));
  out.insert(out.end(), map.begin(), map.end());
  out.insert(out.end(), section.glb.begin(), section.glb.end());
  return out;
}

Result<SceneSection> decode_scne(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  uint32_t map_bytes = 0;
  if (!in.read(&map_bytes)) return bad("shorter than its 4-byte map length");
  if (map_bytes > kMaxSceneMapBytes || map_bytes > in.remaining())
    return bad("map of " + str(map_bytes) + " bytes, only " + str(in.remaining()) + " remain");
  const nlohmann::json map = nlohmann::json::parse(in.current(), in.current() + map_bytes, nullptr,
                                                   /*allow_exceptions=*/false);
  in.skip(map_bytes);
  if (!map.is_object() || !map.contains("meshes") || !map["meshes"].is_array())
    return bad("the map is not a JSON object with a \"meshes\" array");
  SceneSection section;
  for (const nlohmann::json& m : map["meshes"]) {
    const std::string where = "map entry " + str(section.meshes.size());
    if (!m.is_object() || !m.contains("mesh") || !m["mesh"].is_number_unsigned() ||
        !m.contains("group") || !m["group"].is_number_unsigned() || !m.contains("triangles") ||
        !m["triangles"].is_array())
      return bad(where + " is not {\"mesh\": N, \"group\": N, \"triangles\": [...]}");
    if (m["mesh"].get<uint64_t>() > UINT32_MAX || m["group"].get<uint64_t>() > UINT32_MAX)
      return bad(where + ": mesh or group number out of range");
    SceneMeshGroup entry;
    entry.mesh = m["mesh"].get<uint32_t>();
    entry.group = m["group"].get<uint32_t>();
    for (const nlohmann::json& t : m["triangles"]) {
      if (!t.is_number_unsigned()) return bad(where + ": a triangle count is not unsigned");
      entry.triangles.push_back(t.get<uint64_t>());
    }
    section.meshes.push_back(std::move(entry));
  }
  if (map.contains("image_uris")) {
    if (!map["image_uris"].is_array()) return bad("\"image_uris\" is not an array");
    for (const nlohmann::json& uri : map["image_uris"]) {
      if (!uri.is_string()) return bad("an image URI is not a string");
      section.image_uris.push_back(uri.get<std::string>());
    }
  }
  Status checked = check_map(section.meshes);
  if (!checked.is_ok()) return checked;
  uint32_t magic = 0, version = 0, length = 0;
  const size_t glb_start = in.position();
  if (!in.read(&magic) || !in.read(&version) || !in.read(&length))
    return bad("no 12-byte GLB header after the map");
  if (magic != kGlbMagic) return bad("the asset does not start with the GLB magic \"glTF\"");
  if (version != kGlbVersion) return bad("the asset is GLB version " + str(version) + ", not 2");
  if (length != size - glb_start)
    return bad("the GLB header says " + str(length) + " bytes, the section holds " +
               str(size - glb_start));
  section.glb.assign(data + glb_start, data + size);
  return section;
}

}  // namespace lodbake
