// The progressive-mesh step of lodbake-simplify (--pm), shared with
// lodbake-bake so that both write the same bytes: META's options, a
// progressive mesh's sections, the container of a mesh's PM, and every
// mesh's PM with its wedges over an asset.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "formats/mesh/progressive_mesh.h"
#include "formats/scene/scene.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_lods.h"
#include "lib/simplify/simplify.h"

namespace lodbake {

struct SimplifyStepOptions {
  std::string placement = "half";  // as META records it; options.placement agrees
  bool repair = false;
  bool strict = false;
  int quantize_bits = 0;  // the PM's positions; 0: float32
  SimplifyOptions options;
  AttributeWeights weights;  // assets only
};

// META's options of a progressive-mesh container.
nlohmann::json pm_meta_options(const SimplifyStepOptions& request);

// A progressive mesh's sections (BASE + VSPL, quantized with --quantize)
// and META's counts, for a mesh input and for each mesh of an asset alike.
struct PmSections {
  Bytes base, vspl;
  std::map<std::string, uint64_t> counts;
};

Result<PmSections> pm_sections(const SimplifyStepOptions& request, const ProgressiveMesh& pm);

// The container of one mesh's progressive mesh: META (lodbake-simplify,
// the options, `input`, the counts), BASE and VSPL. `sizes` gets each
// section's bytes when not null.
Result<Bytes> pm_container_bytes(const SimplifyStepOptions& request, const MetaInput& input,
                                 const ProgressiveMesh& pm, std::map<std::string, uint64_t>* sizes);

// Every mesh's progressive mesh with its wedges, keyed by scene mesh:
// options.target_triangles is the asset's budget, shared by its meshes in
// proportion to their size (as lodbake-simplify -o ASSET.glb shares it).
Result<std::map<uint32_t, MeshPm>> asset_progressive_meshes(const SimplifyStepOptions& request,
                                                            const Scene& scene);

// One asset mesh's group: BASE, VSPL and WEDG, META's counts and a report.
Result<MeshSections> asset_pm_sections(const SimplifyStepOptions& request, const MeshPm& m);

}  // namespace lodbake
