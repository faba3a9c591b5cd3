// OBJ -> Scene: the OBJ reader's mesh and material groups (lib/meshio),
// split into one sub-mesh per group, each made a primitive by
// primitive_from_mesh().
// Texture coordinates or normals that only some faces have are dropped by
// the plain reader for the whole mesh; here a group keeps them when all its
// faces have them (the usual case: untextured and textured materials in one
// file), and only a group that mixes both drops them, with a note.
#include "lib/scene/obj_scene.h"

#include <algorithm>
#include <limits>
#include <new>
#include <optional>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/scene/obj_materials.h"
#include "lib/scene/scene_from_mesh.h"

namespace lodbake {
namespace {

constexpr uint32_t kUnmapped = std::numeric_limits<uint32_t>::max();

// An old -> new index map reused across groups: clearing only the entries a
// group set keeps the work proportional to the group, not to the file (a
// hostile file may hold many one-face groups over many vertices).
class Renumbering {
 public:
  explicit Renumbering(size_t size) : new_of_old_(size, kUnmapped) {}
  Renumbering(const Renumbering&) = delete;
  Renumbering& operator=(const Renumbering&) = delete;

  // The new index of `old`, the next free one when first asked for.
  uint32_t map(uint32_t old, bool* added) {
    uint32_t& slot = new_of_old_[old];
    *added = slot == kUnmapped;
    if (*added) {
      slot = static_cast<uint32_t>(old_of_new_.size());
      old_of_new_.push_back(old);
    }
    return slot;
  }
  const std::vector<uint32_t>& old_of_new() const { return old_of_new_; }
  void clear() {
    for (uint32_t old : old_of_new_)
      new_of_old_[old] = kUnmapped;
    old_of_new_.clear();
  }

 private:
  std::vector<uint32_t> new_of_old_;
  std::vector<uint32_t> old_of_new_;
};

// How many of `triangles` have an attribute index on every corner of `a`.
size_t triangles_with(const MeshAttribute& a, const std::vector<uint32_t>& triangles) {
  size_t with = 0;
  for (uint32_t t : triangles) {
    const Triangle& c = a.corners[t];
    with += c[0] != kObjNoIndex && c[1] != kObjNoIndex && c[2] != kObjNoIndex ? 1 : 0;
  }
  return with;
}

// `a` restricted to `triangles` of a sub-mesh whose vertex v is the mesh's
// vertex old_of_new[v]: values compacted in order of first use.
MeshAttribute sub_attribute(const MeshAttribute& a, const std::vector<uint32_t>& triangles,
                            const std::vector<uint32_t>& old_of_new, Renumbering* values) {
  MeshAttribute out;
  if (!a.present()) return out;
  out.binding = a.binding;
  out.components = a.components;
  const uint32_t c = a.components;
  if (a.binding == AttributeBinding::kPerVertex) {
    out.values.reserve(old_of_new.size() * c);
    for (uint32_t v : old_of_new)
      out.values.insert(out.values.end(), a.values.begin() + size_t{v} * c,
                        a.values.begin() + size_t{v + 1} * c);
    return out;
  }
  out.corners.reserve(triangles.size());
  for (uint32_t t : triangles) {
    Triangle corner{};
    for (int k = 0; k < 3; ++k) {
      const uint32_t old = a.corners[t][k];
      bool added = false;
      corner[k] = values->map(old, &added);
      if (added) {
        out.values.insert(out.values.end(), a.values.begin() + size_t{old} * c,
                          a.values.begin() + size_t{old + 1} * c);
      }
    }
    out.corners.push_back(corner);
  }
  values->clear();
  return out;
}

// The triangles of one group as a mesh of the vertices they use, numbered
// in order of first use.
// The scratch maps of sub_mesh(), one per index space.
struct SubMeshScratch {
  explicit SubMeshScratch(const TriangleMesh& mesh, const ObjMaterialGroups& groups)
      : vertices(mesh.positions.size()),
        texcoords(std::max(mesh.texcoords.value_count(), groups.partial_texcoords.value_count())),
        normals(std::max(mesh.normals.value_count(), groups.partial_normals.value_count())) {}
  Renumbering vertices;
  Renumbering texcoords;
  Renumbering normals;
};

TriangleMesh sub_mesh(const TriangleMesh& mesh, const std::vector<uint32_t>& triangles,
                      const MeshAttribute& texcoords, const MeshAttribute& normals,
                      SubMeshScratch* scratch) {
  TriangleMesh out;
  Renumbering& vertices = scratch->vertices;
  out.triangles.reserve(triangles.size());
  for (uint32_t t : triangles) {
    Triangle tri{};
    for (int k = 0; k < 3; ++k) {
      bool added = false;
      tri[k] = vertices.map(mesh.triangles[t][k], &added);
    }
    out.triangles.push_back(tri);
  }
  const std::vector<uint32_t>& old_of_new = vertices.old_of_new();
  out.positions.reserve(old_of_new.size());
  for (uint32_t v : old_of_new)
    out.positions.push_back(mesh.positions[v]);
  out.texcoords = sub_attribute(texcoords, triangles, old_of_new, &scratch->texcoords);
  out.normals = sub_attribute(normals, triangles, old_of_new, &scratch->normals);
  vertices.clear();
  return out;
}

// The mesh with `texcoords` and `normals` instead of its own attributes
// (its positions and triangles moved out).
TriangleMesh whole_mesh(TriangleMesh* mesh, const MeshAttribute& texcoords,
                        const MeshAttribute& normals) {
  TriangleMesh out;
  out.texcoords = texcoords;
  out.normals = normals;
  out.positions = std::move(mesh->positions);
  out.triangles = std::move(mesh->triangles);
  return out;
}

// The attribute a group uses: the mesh's own, or the partial one when all
// the group's triangles have it (a note when some do).
const MeshAttribute& group_attribute(const MeshAttribute& whole, const MeshAttribute& partial,
                                     const std::vector<uint32_t>& triangles, const char* what,
                                     const std::string& group, ImportReport* report) {
  static const MeshAttribute kAbsent;
  if (whole.present() || !partial.present()) return whole;
  const size_t with = triangles_with(partial, triangles);
  if (with == triangles.size()) return partial;
  if (with != 0) {
    report->notes.push_back("dropped " + std::string(what) + " of " + group + ": " +
                            std::to_string(triangles.size() - with) + " of " +
                            std::to_string(triangles.size()) + " triangles have none");
  }
  return kAbsent;
}

}  // namespace

Result<Scene> read_obj_scene(const uint8_t* data, size_t size, const std::string& name,
                             const SceneResources& resources, ImportReport* report) {
  ObjMaterialGroups groups;
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_obj(data, size, report, &groups));
  try {
    // Triangles of each group: [0] before any usemtl, [m + 1] material m.
    std::vector<std::vector<uint32_t>> members(groups.materials.size() + 1);
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
      members[static_cast<size_t>(groups.triangle_material[t] + 1)].push_back(
          static_cast<uint32_t>(t));
    size_t non_empty = 0;
    for (const auto& m : members)
      non_empty += m.empty() ? 0 : 1;

    std::vector<std::string> used_names;
    std::vector<ScenePrimitive> primitives;
    std::optional<SubMeshScratch> scratch;
    if (non_empty > 1) scratch.emplace(mesh, groups);
    for (size_t g = 0; g < members.size(); ++g) {
      const std::vector<uint32_t>& triangles = members[g];
      if (triangles.empty()) continue;
      const std::string group =
          g == 0 ? "the faces without a material" : "material '" + groups.materials[g - 1] + "'";
      const MeshAttribute& texcoords =
          group_attribute(mesh.texcoords, groups.partial_texcoords, triangles,
                          "texture coordinates", group, report);
      const MeshAttribute& normals = group_attribute(mesh.normals, groups.partial_normals,
                                                     triangles, "normals", group, report);
      // One group: every vertex stays, as import_mesh() keeps them.
      Result<ScenePrimitive> primitive =
          non_empty == 1
              ? primitive_from_mesh(whole_mesh(&mesh, texcoords, normals))
              : primitive_from_mesh(sub_mesh(mesh, triangles, texcoords, normals, &*scratch));
      if (!primitive.is_ok()) return primitive.status();
      if (g != 0) {
        primitive.value().material = static_cast<int32_t>(used_names.size());
        used_names.push_back(groups.materials[g - 1]);
      }
      primitives.push_back(std::move(primitive).value());
    }

    Scene scene = scene_of_mesh(name, std::move(primitives));
    if (!used_names.empty()) {
      LODBAKE_ASSIGN_OR_RETURN(ObjSceneMaterials materials,
                               obj_materials(used_names, groups.libraries, resources, report));
      scene.materials = std::move(materials.materials);
      scene.textures = std::move(materials.textures);
      scene.images = std::move(materials.images);
    }
    return scene;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the OBJ file");
  }
}

}  // namespace lodbake
