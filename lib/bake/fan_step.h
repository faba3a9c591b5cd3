// The fan-merge hierarchy step, shared by lodbake-fan and lodbake-bake so
// that both write the same bytes: one mesh's BASE and FANH, META's counts
// and options.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/scene/asset_build.h"

namespace lodbake {

struct FanStepOptions {
  bool repair = false;
  bool strict = false;
  FanBuildOptions options;
};

// What one fan build made: the sections after META (BASE, the mesh itself,
// and FANH), META's counts and the report's figures.
struct FanBuilt {
  FanBuildResult result;
  FanhStats stats;
  double seconds = 0;
  Bytes base, fanh;
  std::map<std::string, uint64_t> counts;
};

Result<FanBuilt> build_fan(const FanBuildOptions& options, const TriangleMesh& mesh);

// META (lodbake-fan and its options; input and counts are the caller's).
MetaSection fan_meta(const FanStepOptions& request);

// One asset mesh's group (build_asset()): BASE and FANH, META's counts.
MeshSections fan_mesh_sections(FanBuilt&& built);

}  // namespace lodbake
