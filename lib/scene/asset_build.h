// Structures over a whole asset: a builder tool (lodbake-hierarchy, -fan,
// -strips, -simplify --pm) given a glTF asset, or an asset's container, builds
// its structure for every mesh of the asset, each once however many nodes
// use it, over the mesh's welded topology (its primitives together, so no
// crack opens between materials), and writes one container: META and SCNE
// in group 0, and mesh g's BASE and structure sections in group g, as
// lodbake-pack ASSET lays them out (docs/format.md section 23).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/ingest/load_mesh.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

// What a tool builds from one mesh: its sections (BASE among them), in the
// order they are to be written, its META counts and its report.
struct MeshSections {
  std::vector<std::pair<std::string, Bytes>> sections;
  std::map<std::string, uint64_t> counts;  // META's counts when this is group 0
  nlohmann::json report;
};

// Builds one mesh's sections: `mesh` is the mesh's welded topology after
// the load options' checks and repair (unreferenced points dropped).
using MeshBuilder =
    std::function<Result<MeshSections>(uint32_t scene_mesh, const TriangleMesh& mesh)>;

struct AssetBuild {
  Bytes file;
  // Per group: the scene mesh, its triangles before and after the check's
  // repair, whether it was repaired, and the builder's report.
  std::vector<nlohmann::json> groups;
  std::vector<std::string> warnings;  // one line each
};

// The asset a tool was given (`bytes`, read from `path`): a glTF asset, or
// a container holding an asset (SCNE). Fails with what the reader says.
Result<Scene> read_asset(const std::string& path, const Bytes& bytes,
                         const SceneResources& resources, ImportReport* report);

// True when `path` (already read into `bytes`) is an asset, which every
// tool takes as it takes glTF (docs/import.md "Meshes as scenes"): a glTF
// asset; a container with a SCNE section; an OBJ with materials, i.e. whose
// faces fall into two or more material groups (the faces before any
// 'usemtl' form one) or use a material while a 'mtllib' names a file that
// exists (outside the OBJ's folder too: reading it is then refused, as a
// glTF URI is); a PLY with vertex colours. Any other file is a mesh: OFF,
// STL, .drc, an OBJ without materials (texture coordinates and normals
// alone stay in the mesh, per vertex), a PLY without colours.
bool is_asset(const std::string& path, const Bytes& bytes);

// True when a run that writes a glTF asset (lodbake-simplify -o OUT.glb)
// reads `path` as a scene: an asset file (not a container), or an OBJ with
// texture coordinates, whose seams the scene keeps per corner where the
// mesh would split its vertices.
bool is_scene_source(const std::string& path, const Bytes& bytes);

// `meta` gives tool, options and input; counts come from group 0's
// builder, "scene" from the asset. Deterministic.
Result<AssetBuild> build_asset(const Scene& scene, MetaSection meta, const LoadOptions& load,
                               const MeshBuilder& build);

}  // namespace lodbake
