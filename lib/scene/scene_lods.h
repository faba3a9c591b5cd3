// Simplifying a whole asset: each mesh once, however many nodes use it,
// all its primitives together on one welded topology (so no crack opens
// between materials), and the scene rebuilt around the simplified meshes
// with every material, texture, node, skin and animation kept.
//
// Each mesh is collapsed with its wedges (lib/simplify/wedge_collapse.h):
// a vertex of a primitive is a wedge of its point, the cost counts the
// normals, texture coordinates, colours and tangents a collapse distorts
// (weights below), texture seams and material borders move only along
// themselves, and a corner always keeps the values of a vertex of its own
// primitive. docs/simplify.md, "Assets (glTF scenes)".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/ingest/load_mesh.h"
#include "lib/simplify/simplify.h"
#include "lib/simplify/wedge_collapse.h"

namespace lodbake {

// How much an attribute's difference costs next to a distance: a weighted
// difference of 1 spread over a distance d costs about what moving the
// surface by d does (meshoptimizer's convention, with distances relative
// to the bounding-box diagonal; docs/simplify.md gives the defaults'
// measure). 0 leaves the stream out of the error.
struct AttributeWeights {
  double normal = 0.3;    // NORMAL (unit vectors)
  double texcoord = 5.0;  // every TEXCOORD_n
  double color = 1.0;     // every COLOR_n (RGB or RGBA, 0 to 1)
  double tangent = 0.1;   // TANGENT's xyz (its w is a sign: a difference is a seam)
};

struct SceneLodOptions {
  // Placement must be kHalf (a corner then moves to a point of the input).
  // Its stop criteria apply to each mesh; `ratios` overrides target_ratio.
  SimplifyOptions simplify;
  // The levels, each a ratio of every mesh's triangles; empty: one level,
  // where `simplify`'s stop criteria leave each mesh.
  std::vector<double> ratios;
  // repair / strict as the tools' options say; the policy is the engine's.
  LoadOptions load;
  AttributeWeights weights;
};

struct MeshLodReport {
  uint32_t mesh = 0;
  uint64_t input_triangles = 0;
  bool repaired = false;                // the default repair (or --repair) ran
  std::vector<uint64_t> lod_triangles;  // per level
  std::vector<uint64_t> lod_targets;    // per level: the triangles asked for (0: no target)
  // Wedges that kept their values at another point (a seam moved, only with
  // `permissive`), at the last level.
  uint64_t moved_wedges = 0;
  // When a level stopped above its target: what held the mesh (no legal
  // collapse was left, or max_error was reached).
  std::optional<CollapseBlocks> blocked;
};

struct SceneLods {
  std::vector<Scene> levels;          // one scene per level, in `ratios` order
  std::vector<MeshLodReport> meshes;  // per mesh with triangles
};

// A mesh's progressive mesh with its wedges: the collapses of
// simplify_scene() recorded down to the smallest target (0 without one), so
// the level with a level's vertex count has that level's triangles.
struct MeshPm {
  uint32_t mesh = 0;
  bool repaired = false;
  // Positions and connectivity; input_vertex maps to the mesh's welded
  // (and repaired) points. No attribute streams: the wedges carry them.
  ProgressiveMesh pm;
  // The wedge table names (primitive, vertex) pairs of the scene mesh.
  PmWedges wedges;
  std::optional<CollapseBlocks> blocked;  // the base stopped above the target
};

// A mesh's corners as the builders see it: the welded, repaired topology
// build_asset() gives a MeshBuilder, and each corner's wedge, a (primitive,
// vertex) pair of the scene mesh. What a structure built over the topology
// alone (the balanced hierarchy's progressive mesh) takes its wedges from.
struct MeshCornerWedges {
  uint32_t mesh = 0;
  TriangleMesh topology;
  std::vector<std::array<uint32_t, 3>> corner_wedge;  // per triangle of topology
  std::vector<uint32_t> wedge_point;                  // per wedge, a vertex of topology
  std::vector<uint32_t> wedge_primitive;
  std::vector<uint32_t> wedge_vertex;
};

// One per mesh with triangles, in mesh order; fails as simplify_scene().
Result<std::vector<MeshCornerWedges>> scene_corner_wedges(const Scene& scene,
                                                          const LoadOptions& load);

// The wedges of `pm`, a progressive mesh over `corners.topology` (its
// input_vertex naming topology vertices), by assign_pm_wedges()'s rule,
// the wedge table filled.
Result<PmWedges> wedges_of_pm(const ProgressiveMesh& pm, const MeshCornerWedges& corners);

// Needs every mesh's point_of_vertex filled. Fails with the mesh's number
// when a mesh cannot be simplified (kInvalidInput for a mesh the engine
// cannot take, naming its problem).
Result<SceneLods> simplify_scene(const Scene& scene, const SceneLodOptions& options);

// One MeshPm per mesh with triangles, as simplify_scene() fails.
Result<std::vector<MeshPm>> scene_progressive_meshes(const Scene& scene,
                                                     const SceneLodOptions& options);

// The primitives of `mesh` at one level of its progressive mesh: `level`
// (PM vertex ids, e.g. WedgeRefiner::mesh()) whose corners use `corners`
// of `wedges`. Points and lines primitives are kept; a triangle primitive
// with no triangle at this level is left out. Every index is checked
// (kInvalidInput): the wedges may come from a file.
Result<std::vector<ScenePrimitive>> primitives_at_level(
    const SceneMesh& mesh, const TriangleMesh& level,
    const std::vector<std::array<uint32_t, 3>>& corners, const PmWedges& wedges);

}  // namespace lodbake
