// The balanced vertex hierarchy step, shared by lodbake-hierarchy and
// lodbake-bake so that both write the same bytes: the hierarchy of one mesh
// and the sections asked for (VHIE + RFIN, VSPL + DAGE, VSPL + VTRE), with
// BASE first, and META's options.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/vhie.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_lods.h"

namespace lodbake {

struct HierarchyStepOptions {
  std::string sections = "vhie,dage,vtre";
  bool vhie = false;  // the parsed `sections`
  bool dage = false;
  bool vtre = false;
  bool repair = false;
  bool strict = false;
  BalancedBuildOptions options;
};

// Sets vhie, dage and vtre from `options->sections` ("vhie,dage,vtre", any
// subset; meta and base are accepted and always written). kUsage with the
// message a tool prints when an item is unknown or none is a structure.
Status parse_hierarchy_sections(HierarchyStepOptions* options);

// One section to write: its tag, payload and what its bytes-per-item figure
// divides by (the required flag is the registry's, as for every writer).
struct HierarchySection {
  const char* tag;
  Bytes bytes;
  const char* per_what;  // "node", "split" or nullptr
  uint64_t per_count;
};

// What one build made, besides its sections: for the reports.
struct HierarchyBuilt {
  std::vector<HierarchySection> sections;  // BASE first (META is the caller's)
  HierarchyShape shape;
  BalancedBuildStats stats;
  TriangleMesh base;
  std::vector<std::pair<std::string, double>> build_seconds;  // in build order
  nlohmann::json dag_report, vtre_report;
  std::map<std::string, uint64_t> counts;  // META's
  ProgressiveMesh pm;                      // the hierarchy's own, when DAGE or VTRE are built
};

Result<HierarchyBuilt> build_hierarchy_sections(const HierarchyStepOptions& request,
                                                const TriangleMesh& mesh);

// META's options of a hierarchy container.
nlohmann::json hierarchy_meta_options(const HierarchyStepOptions& request);

// Every mesh's corners with their wedges (scene_corner_wedges()), keyed by
// scene mesh, for the WEDG of the hierarchy's progressive mesh over an asset.
Result<std::map<uint32_t, MeshCornerWedges>> asset_corner_wedges(
    const HierarchyStepOptions& request, const Scene& scene);

// One asset mesh's group (build_asset()): the built sections, with the
// WEDG of the hierarchy's progressive mesh after its VSPL (the corners read
// from the scene must be over `mesh`, the mesh built), and a report.
Result<MeshSections> hierarchy_mesh_sections(HierarchyBuilt&& built,
                                             const std::map<uint32_t, MeshCornerWedges>& corners,
                                             uint32_t scene_mesh, const TriangleMesh& mesh);

}  // namespace lodbake
