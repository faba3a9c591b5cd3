#include "lib/bake/hierarchy_step.h"

#include <chrono>
#include <functional>
#include <sstream>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/sections/wedg.h"
#include "lib/bake/asset_pm_wedges.h"
#include "lib/core/parallel.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/simplify/pm_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"

namespace lodbake {

Status parse_hierarchy_sections(HierarchyStepOptions* options) {
  options->vhie = options->dage = options->vtre = false;
  std::stringstream list(options->sections);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item == "vhie") {
      options->vhie = true;
    } else if (item == "dage") {
      options->dage = true;
    } else if (item == "vtre") {
      options->vtre = true;
    } else if (item != "meta" && item != "base") {
      return Status(ErrorKind::kUsage,
                    "--sections: '" + item +
                        "' is not a section lodbake-hierarchy builds (vhie, dage, vtre)");
    }
  }
  if (!options->vhie && !options->dage && !options->vtre)
    return Status(ErrorKind::kUsage, "--sections must include vhie, dage or vtre");
  return Status::ok();
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// The hierarchy and the sections --sections asks for, from one mesh.
Result<HierarchyBuilt> build_hierarchy_sections(const HierarchyStepOptions& request,
                                                const TriangleMesh& mesh) {
  using Clock = std::chrono::steady_clock;
  HierarchyBuilt out;
  Clock::time_point start = Clock::now();
  LODBAKE_ASSIGN_OR_RETURN(BalancedHierarchy built,
                           build_balanced_hierarchy(mesh, request.options));
  out.build_seconds.emplace_back("hierarchy", seconds_since(start));
  const VertexHierarchy& h = built.hierarchy;
  out.shape = hierarchy_shape(h);
  out.stats = built.stats;
  const HierarchyShape& shape = out.shape;
  std::vector<HierarchySection>& sections = out.sections;
  // VHIE + RFIN need the hierarchy alone, DAGE and VTRE its progressive
  // mesh alone: DAGE and VTRE are built side by side (when there are two
  // threads), each writing its own slots, assembled below in section order.
  const ParallelScope threads(request.options.threads);
  double refinement_seconds = 0, pm_seconds = 0, dag_seconds = 0, vtre_seconds = 0;
  Status refined = Status::ok(), converted = Status::ok(), dag_made = Status::ok(),
         vtre_made = Status::ok();
  Bytes vhie, rfin, vspl, dage, vtre;
  uint64_t dag_nodes = 0, vtre_nodes = 0;
  auto refine = [&]() -> Status {
    const Clock::time_point began = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(std::vector<NodeRefinement> refinement,
                             compute_refinement_data(h, mesh));
    refinement_seconds = seconds_since(began);
    LODBAKE_ASSIGN_OR_RETURN(vhie, encode_vhie(h));
    LODBAKE_ASSIGN_OR_RETURN(rfin, encode_rfin(h, refinement));
    return Status::ok();
  };
  // DAGE and VTRE describe a progressive mesh: the hierarchy's own, so they
  // share BASE with VHIE (a greedy PM given as input has another base mesh).
  ProgressiveMesh& pm = out.pm;
  // Once its progressive mesh is made, only the hierarchy's base mesh is
  // read again: the rest is freed before the DAG and the vertex trees.
  bool released = false;
  auto release_hierarchy = [&] {
    if (released) return;
    out.base = std::move(built.hierarchy.base);
    built.hierarchy = VertexHierarchy();
    released = true;
  };
  auto build_dag = [&]() -> Status {
    const Clock::time_point began = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VsplitDag dag, build_vsplit_dag(pm));
    dag_seconds = seconds_since(began);
    LODBAKE_ASSIGN_OR_RETURN(dage, encode_dage(dag));
    LODBAKE_ASSIGN_OR_RETURN(DageSummary summary, read_dage_summary(dage.data(), dage.size()));
    out.dag_report = {{"nodes", summary.node_count},
                      {"edges", summary.edge_count},
                      {"roots", summary.root_count},
                      {"leaves", summary.leaf_count}};
    dag_nodes = dag.node_count();
    return Status::ok();
  };
  auto build_trees = [&]() -> Status {
    const Clock::time_point began = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, build_vertex_trees(pm));
    vtre_seconds = seconds_since(began);
    LODBAKE_ASSIGN_OR_RETURN(vtre, encode_vtre(trees));
    const VtreRecordSizes rec = vtre_record_sizes(trees);
    auto bytes_per = [](uint64_t bits, uint64_t count) {
      return count == 0 ? nlohmann::json(nullptr)
                        : nlohmann::json(static_cast<double>(bits) / 8.0 / count);
    };
    out.vtre_report = {{"nodes", trees.node_count()},
                       {"base_record_bytes", bytes_per(rec.base_bits, rec.base_records)},
                       {"left_record_bytes", bytes_per(rec.left_bits, rec.left_records)},
                       {"right_record_bytes", bytes_per(rec.right_bits, rec.right_records)}};
    vtre_nodes = trees.node_count();
    return Status::ok();
  };
  auto convert = [&]() -> Status {
    const Clock::time_point began = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(pm, hierarchy_to_progressive_mesh(h));
    pm_seconds = seconds_since(began);
    release_hierarchy();
    LODBAKE_ASSIGN_OR_RETURN(vspl, encode_vspl(pm, VsplEncodeOptions()));
    std::vector<std::function<void()>> after;
    if (request.dage) after.emplace_back([&] { dag_made = build_dag(); });
    if (request.vtre) after.emplace_back([&] { vtre_made = build_trees(); });
    threads.for_each_part(after.size(), [&](size_t k) { after[k](); });
    return Status::ok();
  };
  // The two chains one after the other: side by side they held both
  // chains' structures at once (the 3.49M-triangle dragon: 1.31 GB with 2
  // threads against 0.94 GB with 1) for the refinement's short time.
  if (request.vhie) refined = refine();
  if (refined.is_ok() && (request.dage || request.vtre)) converted = convert();
  // The first failure in section order, as the steps one after the other.
  LODBAKE_RETURN_IF_ERROR(refined);
  LODBAKE_RETURN_IF_ERROR(converted);
  LODBAKE_RETURN_IF_ERROR(dag_made);
  LODBAKE_RETURN_IF_ERROR(vtre_made);
  if (request.vhie) {
    out.build_seconds.emplace_back("refinement", refinement_seconds);
    sections.push_back({kVhieTag, std::move(vhie), "node", shape.nodes});
    sections.push_back({kRfinTag, std::move(rfin), "split", shape.splits});
  }
  if (request.dage || request.vtre) {
    out.build_seconds.emplace_back("progressive_mesh", pm_seconds);
    sections.push_back({kVsplTag, std::move(vspl), "split", pm.splits.size()});
  }
  if (request.dage) {
    out.build_seconds.emplace_back("dag", dag_seconds);
    sections.push_back({kDageTag, std::move(dage), "node", dag_nodes});
  }
  if (request.vtre) {
    out.build_seconds.emplace_back("vertex_trees", vtre_seconds);
    sections.push_back({kVtreTag, std::move(vtre), "node", vtre_nodes});
  }
  release_hierarchy();
  out.counts = {
      {"vertices", out.base.vertex_count()},   {"triangles", out.base.triangle_count()},
      {"hierarchy_nodes", shape.nodes},        {"hierarchy_depth", shape.depth},
      {"input_vertices", mesh.vertex_count()}, {"input_triangles", mesh.triangle_count()}};
  if (request.dage || request.vtre) {
    out.counts["splits"] = pm.splits.size();
    out.counts["full_vertices"] = pm.full_vertex_count();
    out.counts["full_triangles"] = full_triangle_count(pm.base.triangle_count(), pm.splits);
  }
  LODBAKE_ASSIGN_OR_RETURN(Bytes base_bytes, encode_base(out.base, BaseEncodeOptions()));
  sections.insert(sections.begin(), {kBaseTag, std::move(base_bytes), nullptr, 0});
  return out;
}

nlohmann::json hierarchy_meta_options(const HierarchyStepOptions& request) {
  return {{"sections", request.sections},
          {"boundary_weight", request.options.boundary_weight},
          {"max_normal_change_degrees", request.options.max_normal_change_degrees},
          {"repair", request.repair}};
}

Result<std::map<uint32_t, MeshCornerWedges>> asset_corner_wedges(
    const HierarchyStepOptions& request, const Scene& scene) {
  return read_asset_corners(scene, request.repair, request.strict);
}

Result<MeshSections> hierarchy_mesh_sections(HierarchyBuilt&& b,
                                             const std::map<uint32_t, MeshCornerWedges>& corners,
                                             uint32_t scene_mesh, const TriangleMesh& mesh) {
  MeshSections out;
  for (HierarchySection& w : b.sections) {
    const bool vspl = std::string(w.tag) == kVsplTag;
    out.sections.emplace_back(w.tag, std::move(w.bytes));
    if (!vspl) continue;
    LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, encode_asset_pm_wedges(b.pm, corners, scene_mesh, mesh));
    out.sections.emplace_back(kWedgTag, std::move(wedg));
  }
  out.counts = b.counts;
  out.report = {{"nodes", b.shape.nodes},
                {"splits", b.shape.splits},
                {"depth", b.shape.depth},
                {"base_triangles", b.base.triangle_count()}};
  return out;
}

}  // namespace lodbake
