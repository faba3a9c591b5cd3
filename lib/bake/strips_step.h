// The strips step, shared by lodbake-strips and lodbake-bake so that both
// write the same bytes: triangle strips of a mesh (--strips-only: BASE +
// STRP) or strips and the SETS graph over a progressive mesh (BASE + VSPL +
// SETS), META's options and the container.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/bake/asset_pm_wedges.h"
#include "lib/scene/asset_build.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/stripify.h"

namespace lodbake {

struct StripsStepOptions {
  bool strips_only = false;
  bool repair = false;
  bool strict = false;
  /// Threads for the progressive mesh's simplification and the SETS graph
  /// (lib/core/parallel.h): 0, the caller's task arena (every core, or a
  /// bake's --jobs threads). The output does not depend on it.
  unsigned threads = 0;
};

// What the input gives: a mesh (strips-only), or a progressive mesh.
struct StripsInput {
  MetaInput meta;
  TriangleMesh mesh;                          // strips-only: the mesh the strips index
  std::shared_ptr<const ProgressiveMesh> pm;  // full mode (a bake shares it with simplify)
  nlohmann::json report;
};

// What one build made: the sections after META, META's counts, and the
// report's "strips", "sets" and "sections".
struct StripsBuilt {
  std::vector<std::pair<std::string, Bytes>> sections;
  std::map<std::string, uint64_t> counts;
  nlohmann::json report = nlohmann::json::object();
  StripifyStats strip_stats;
  uint64_t stripped_vertices = 0, stripped_triangles = 0;
};

// The simplification whose progressive mesh the strips' graph follows: QEM
// half-edge collapses as far as legal.
SimplifyOptions strips_pm_options(unsigned threads);

// That progressive mesh.
Result<ProgressiveMesh> record_pm(const TriangleMesh& mesh, std::function<void(double)> progress,
                                  unsigned threads = 0);

// The strips (and without strips_only the SETS graph) of one input, for a
// mesh or container input and for each mesh of an asset alike.
Result<StripsBuilt> build_strips(const StripsStepOptions& request, const StripsInput& in);

MetaSection strips_meta(const StripsStepOptions& request);

// META (strips_meta(), in.meta, the counts) and the built sections.
Result<Bytes> strips_container(const StripsStepOptions& request, const StripsInput& in,
                               StripsBuilt built);

// One asset mesh's group (build_asset()). Without strips_only, `corners`
// (read_asset_corners(), which must hold `scene_mesh`'s corners over
// `mesh`) gives the WEDG written after the progressive mesh's VSPL: its
// levels, and so every SETS level, carry the asset's wedges. STRP (with
// strips_only) holds positions only.
Result<MeshSections> strips_mesh_sections(const StripsStepOptions& request,
                                          const AssetCorners& corners, uint32_t scene_mesh,
                                          const TriangleMesh& mesh);

}  // namespace lodbake
