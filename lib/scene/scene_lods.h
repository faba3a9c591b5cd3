// Simplifying a whole asset: each mesh once, however many nodes use it,
// all its primitives together on one welded topology (so no crack opens
// between materials), and the scene rebuilt around the simplified meshes
// with every material, texture, node, skin and animation kept.
//
// Attributes ride along with the half-edge collapses: a corner keeps the
// attribute values of a vertex of its own primitive at the point it moved
// to (the one whose values are closest to the corner's before, when a seam
// gives that point several), and only where its primitive has no vertex at
// that point (a collapse across a material border) it keeps its own values
// at the new position. The attribute-aware error (issue "attribute-aware
// simplification") is not in the cost yet: the collapse order is the
// geometric QEM's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/ingest/load_mesh.h"
#include "lib/simplify/simplify.h"

namespace lodbake {

struct SceneLodOptions {
  // Placement must be kHalf (a corner then moves to a point of the input).
  // Its stop criteria apply to each mesh; `ratios` overrides target_ratio.
  SimplifyOptions simplify;
  // The levels, each a ratio of every mesh's triangles; empty: one level,
  // where `simplify`'s stop criteria leave each mesh.
  std::vector<double> ratios;
  // repair / strict as the tools' options say; the policy is the engine's.
  LoadOptions load;
};

struct MeshLodReport {
  uint32_t mesh = 0;
  uint64_t input_triangles = 0;
  bool repaired = false;                // the default repair (or --repair) ran
  std::vector<uint64_t> lod_triangles;  // per level
  uint64_t borrowed_corners = 0;        // corners that kept their own values across a border
};

struct SceneLods {
  std::vector<Scene> levels;          // one scene per level, in `ratios` order
  std::vector<MeshLodReport> meshes;  // per mesh with triangles
};

// Needs every mesh's point_of_vertex filled. Fails with the mesh's number
// when a mesh cannot be simplified (kInvalidInput for a mesh the engine
// cannot take, naming its problem).
Result<SceneLods> simplify_scene(const Scene& scene, const SceneLodOptions& options);

}  // namespace lodbake
