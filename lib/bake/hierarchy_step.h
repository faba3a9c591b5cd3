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

#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/vhie.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/scene/asset_build.h"

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
};

Result<HierarchyBuilt> build_hierarchy_sections(const HierarchyStepOptions& request,
                                                const TriangleMesh& mesh);

// META's options of a hierarchy container.
nlohmann::json hierarchy_meta_options(const HierarchyStepOptions& request);

// One asset mesh's group (build_asset()): the built sections and a report.
MeshSections hierarchy_mesh_sections(HierarchyBuilt&& built);

}  // namespace lodbake
