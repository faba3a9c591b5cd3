// MTL -> glTF metallic-roughness, the approximations documented in
// docs/import.md ("Meshes as scenes"):
// - baseColorFactor: Kd (1 1 1 when absent) with the opacity (d, or 1 - Tr)
//   as alpha; alphaMode BLEND when that is below 1. map_Kd becomes
//   baseColorTexture (the spec multiplies the map by Kd, as glTF does).
// - metallicFactor: Pm when given, else 0: classic OBJ materials are
//   dielectrics, and glTF's default of 1 would make them metal.
// - roughnessFactor: Pr when given; else from the Blinn-Phong exponent Ns,
//   alpha = sqrt(2 / (Ns + 2)) (Walter et al. 2007, "Microfacet Models for
//   Refraction", eq. 33's Phong-Beckmann match) and roughness = sqrt(alpha)
//   (glTF's alpha = roughness^2); 1 when Ks is black (no highlight) or Ns is
//   absent.
// - emissiveFactor: Ke (clamped to [0, 1]); map_Ke becomes emissiveTexture,
//   with factor 1 1 1 when Ke is absent (glTF's default factor is 0).
// - norm / map_Bump / bump become normalTexture: exporters (Blender among
//   them) write tangent-space normal maps there; a true height map will look
//   wrong, which no conversion here could fix.
// Images are referenced by their path relative to the OBJ's folder (the
// map's name taken relative to its library's folder); one image and one
// texture per distinct path, in order of first use.
// A library or image that is missing is a warning; one that the folder
// confinement refuses (outside the folder, a scheme) fails the read, as a
// glTF URI does, unless the OBJ is read from memory.
#include "lib/scene/obj_materials.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <new>

#include "lib/meshio/file_name.h"
#include "lib/scene/mtl_reader.h"

namespace lodbake {
namespace {

// The float as the shortest decimal that reads back as it, so that the JSON
// says 0.8 rather than 0.800000011920929.
double tidy(float f) {
  char buf[32];
  auto end = std::to_chars(buf, buf + sizeof(buf), f).ptr;
  double d = 0;
  std::from_chars(buf, end, d);
  return d;
}

float unit(float f) {
  return std::clamp(f, 0.0f, 1.0f);
}

std::string folder_of(const std::string& path) {
  size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// Whether a failed read of a library or image is only missing (a warning)
// rather than refused (the read fails).
bool only_missing(const Status& status, const SceneResources& resources) {
  return status.kind() == ErrorKind::kIo || resources.folder.empty();
}

std::string mime_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "png") return "image/png";
  if (ext == "jpg" || ext == "jpeg") return "image/jpeg";
  return "";
}

class MaterialBuilder {
 public:
  MaterialBuilder(const SceneResources& resources, ImportReport* report)
      : resources_(resources), report_(report) {}

  SceneJson material(const MtlMaterial& m, const std::string& library_folder) {
    SceneJson out = SceneJson::object();
    out["name"] = m.name;
    SceneJson pbr = SceneJson::object();
    const float alpha = m.dissolve ? unit(*m.dissolve) : 1.0f;
    if (m.kd || alpha < 1.0f) {
      const MtlColour kd = m.kd.value_or(MtlColour{1, 1, 1});
      pbr["baseColorFactor"] = {tidy(unit(kd[0])), tidy(unit(kd[1])), tidy(unit(kd[2])),
                                tidy(alpha)};
    }
    if (alpha < 1.0f) out["alphaMode"] = "BLEND";
    if (!m.diffuse_map.empty())
      pbr["baseColorTexture"] = {{"index", texture(library_folder + m.diffuse_map)}};
    pbr["metallicFactor"] = m.metallic ? tidy(unit(*m.metallic)) : 0.0;
    if (std::optional<float> r = roughness(m)) pbr["roughnessFactor"] = tidy(*r);
    out["pbrMetallicRoughness"] = std::move(pbr);
    if (!m.normal_map.empty())
      out["normalTexture"] = {{"index", texture(library_folder + m.normal_map)}};
    MtlColour ke = m.ke.value_or(MtlColour{0, 0, 0});
    if (!m.emissive_map.empty()) {
      if (!m.ke) ke = {1, 1, 1};
      out["emissiveTexture"] = {{"index", texture(library_folder + m.emissive_map)}};
    }
    if (ke[0] > 0 || ke[1] > 0 || ke[2] > 0)
      out["emissiveFactor"] = {tidy(unit(ke[0])), tidy(unit(ke[1])), tidy(unit(ke[2]))};
    return out;
  }

  // The first refusal of an image's read, or OK.
  const Status& status() const { return status_; }

  ObjSceneMaterials finish(SceneJson materials) {
    ObjSceneMaterials out;
    out.materials = std::move(materials);
    if (!images_.empty()) out.textures = std::move(textures_);
    out.images = std::move(images_);
    return out;
  }

 private:
  static std::optional<float> roughness(const MtlMaterial& m) {
    if (m.roughness) return unit(*m.roughness);
    if (!m.ns) return std::nullopt;
    if (m.ks && (*m.ks)[0] <= 0 && (*m.ks)[1] <= 0 && (*m.ks)[2] <= 0) return 1.0f;
    const float ns = std::max(*m.ns, 0.0f);
    return unit(std::sqrt(std::sqrt(2.0f / (ns + 2.0f))));
  }

  // The texture index for the image at `path` (relative to the OBJ's folder).
  size_t texture(const std::string& path) {
    auto it = texture_of_path_.find(path);
    if (it != texture_of_path_.end()) return it->second;
    SceneImage image;
    image.uri = path;
    image.mime_type = mime_of(path);
    Result<Bytes> bytes = read_resource(resources_, path);
    if (bytes.is_ok()) {
      image.bytes = std::move(bytes).value();
    } else if (!only_missing(bytes.status(), resources_)) {
      if (status_.is_ok())
        status_ = Status(bytes.status().kind(),
                         "texture '" + path.substr(0, 200) + "': " + bytes.status().message());
    } else {
      image.missing = true;
      report_->warnings.push_back("texture '" + path +
                                  "' cannot be read: " + bytes.status().message());
    }
    const size_t index = images_.size();
    images_.push_back(std::move(image));
    textures_.push_back({{"source", index}});
    texture_of_path_.emplace(path, index);
    return index;
  }

  const SceneResources& resources_;
  ImportReport* report_;
  std::vector<SceneImage> images_;
  SceneJson textures_ = SceneJson::array();
  std::map<std::string, size_t> texture_of_path_;
  Status status_;
};

}  // namespace

Result<ObjSceneMaterials> obj_materials(const std::vector<std::string>& names,
                                        const std::vector<std::string>& libraries,
                                        const SceneResources& resources, ImportReport* report) {
  try {
    // name -> (material, its library's folder); the first library wins.
    std::map<std::string, std::pair<MtlMaterial, std::string>> defined;
    bool every_library_read = true;
    for (const std::string& library : libraries) {
      Result<Bytes> bytes = read_resource(resources, library);
      if (!bytes.is_ok()) {
        if (!only_missing(bytes.status(), resources))
          return Status(bytes.status().kind(), "material library '" + library.substr(0, 200) +
                                                   "': " + bytes.status().message());
        every_library_read = false;
        report->warnings.push_back("material library '" + library +
                                   "' cannot be read: " + bytes.status().message());
        continue;
      }
      LODBAKE_ASSIGN_OR_RETURN(std::vector<MtlMaterial> materials,
                               parse_mtl(bytes.value().data(), bytes.value().size(), report));
      for (MtlMaterial& m : materials) {
        std::string name = m.name;
        defined.emplace(std::move(name), std::make_pair(std::move(m), folder_of(library)));
      }
    }
    MaterialBuilder builder(resources, report);
    SceneJson materials = SceneJson::array();
    for (const std::string& name : names) {
      auto it = defined.find(name);
      if (it != defined.end()) {
        materials.push_back(builder.material(it->second.first, it->second.second));
        continue;
      }
      const std::string message =
          "material '" + name + "' is not defined in " +
          (libraries.empty() ? "any material library (no 'mtllib')" : "the material libraries");
      if (every_library_read) {
        report->warnings.push_back(message);
      } else {
        report->notes.push_back(message);
      }
      MtlMaterial undefined;
      undefined.name = name;
      materials.push_back(builder.material(undefined, ""));
    }
    LODBAKE_RETURN_IF_ERROR(builder.status());
    return builder.finish(std::move(materials));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the materials");
  }
}

}  // namespace lodbake
