#include "lib/bake/bake_steps.h"

#include <algorithm>
#include <cstdio>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/meta.h"
#include "lib/bake/fan_step.h"
#include "lib/bake/hierarchy_step.h"
#include "lib/bake/pack_step.h"
#include "lib/bake/simplify_step.h"
#include "lib/bake/strips_step.h"
#include "lib/ingest/load_mesh.h"
#include "lib/ingest/meta_input.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/pack/pack_containers.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"
#include "lib/scene/scene_pack.h"
#include "lib/simplify/lod_chain.h"

namespace lodbake {
namespace {

LoadOptions load_options(const nlohmann::json& options) {
  LoadOptions load;
  load.repair = options["repair"] == "repair";
  load.strict = options["repair"] == "strict";
  load.drop_unreferenced = true;
  return load;
}

// Load options as a key: equal keys, the same prepared mesh.
std::string load_key(const LoadOptions& options) {
  return std::to_string(options.repair) + std::to_string(options.strict) +
         std::to_string(options.per_vertex_attributes) + std::to_string(options.drop_unreferenced);
}

std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

// Every option that can change simplify()'s result, exactly (threads and
// progress cannot); empty when the options are not to be shared. The
// structured binding names every field of SimplifyOptions: a field added
// there stops the build here until it is looked at and added to the key.
std::string simplify_key(const SimplifyOptions& o) {
  const auto& [placement, target_triangles, target_ratio, max_error, boundary_weight, lock_border,
               locked_vertices, max_normal_change_degrees, permissive, seam_release, height_guard,
               height_guard_factor, record_pm, threads, progress] = o;
  (void)threads;   // the result is the same bytes for any count
  (void)progress;  // a callback, not an input
  if (!locked_vertices.empty()) return "";
  auto optional = [](const std::optional<double>& value) {
    return value ? exact(*value) : std::string("-");
  };
  return std::to_string(static_cast<int>(placement)) + " " +
         (target_triangles ? std::to_string(*target_triangles) : std::string("-")) + " " +
         optional(target_ratio) + " " + optional(max_error) + " " + exact(boundary_weight) + " " +
         std::to_string(lock_border) + " " + exact(max_normal_change_degrees) + " " +
         std::to_string(permissive) + " " + optional(seam_release) + " " +
         std::to_string(height_guard) + " " + exact(height_guard_factor) + " " +
         std::to_string(record_pm);
}

// Loads a mesh input as the tools' load_input() does; its notes and
// warnings go to the step's warnings.
Status load(InputMeshes* meshes, const std::string& input, const Bytes& bytes,
            const LoadOptions& options, std::shared_ptr<const LoadedMesh>* shared,
            StepResult* out) {
  LODBAKE_ASSIGN_OR_RETURN(*shared, meshes->load(input, bytes, options));
  const LoadedMesh* loaded = shared->get();
  for (const std::string& warning : loaded->import.warnings)
    out->warnings.push_back(warning);
  const MeshCheckReport& check =
      loaded->check_after_repair ? *loaded->check_after_repair : loaded->check;
  for (MeshProblem problem : kAllMeshProblems) {
    if (problem == MeshProblem::kUnreferencedVertices) continue;
    if (check.count(problem) != 0)
      out->warnings.push_back("kept as it is: " + check.describe(problem));
  }
  if (loaded->repair) out->report["repaired"] = true;
  return Status::ok();
}

Result<Scene> read_input_asset(const std::string& input, const Bytes& bytes, StepResult* out) {
  ImportReport imported;
  LODBAKE_ASSIGN_OR_RETURN(Scene scene, read_asset(input, bytes, SceneResources{}, &imported));
  for (const std::string& warning : imported.warnings)
    out->warnings.push_back(warning);
  return scene;
}

// A builder's run over an asset, as tools/common's run_asset_build().
Status build_over_asset(const std::string& input, const Bytes& bytes, MetaSection meta,
                        const LoadOptions& load, const MeshBuilder& build,
                        const std::function<Status(const Scene&)>& on_scene, StepResult* out) {
  LODBAKE_ASSIGN_OR_RETURN(Scene scene, read_input_asset(input, bytes, out));
  if (on_scene) LODBAKE_RETURN_IF_ERROR(on_scene(scene));
  LoadOptions asset_load;
  asset_load.repair = load.repair;
  asset_load.strict = load.strict;
  meta.input = asset_meta_input(input, bytes);
  LODBAKE_ASSIGN_OR_RETURN(AssetBuild built,
                           build_asset(scene, std::move(meta), asset_load, build));
  for (const std::string& warning : built.warnings)
    out->warnings.push_back(warning);
  out->report["groups"] = built.groups.size();
  out->files.emplace_back("", std::move(built.file));
  return Status::ok();
}

Status run_pack(const nlohmann::json& o, const std::string& input, const Bytes& bytes,
                InputMeshes* meshes, StepResult* out) {
  const int quantize = o["quantize"].get<int>();
  if (is_asset(input, bytes)) {
    ImportReport imported;
    LODBAKE_ASSIGN_OR_RETURN(Scene scene,
                             read_scene_bytes(input, bytes, SceneResources{}, &imported));
    for (const std::string& warning : imported.warnings)
      out->warnings.push_back(warning);
    MetaSection meta = make_meta("lodbake-pack");
    meta.options = pack_meta_options(false, quantize);
    meta.input = asset_meta_input(input, bytes);
    BaseEncodeOptions encoding;
    encoding.quantize = quantize != 0;
    if (encoding.quantize) encoding.bits = quantize;
    LODBAKE_ASSIGN_OR_RETURN(ScenePackResult packed, pack_scene(scene, meta, encoding));
    for (const std::string& warning : packed.warnings)
      out->warnings.push_back(warning);
    out->files.emplace_back("", std::move(packed.file));
    return Status::ok();
  }
  const LoadOptions load_with = load_options(o);
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_with, &loaded, out));
  LODBAKE_ASSIGN_OR_RETURN(PackedMesh packed, pack_mesh(loaded->mesh, meta_input(input, *loaded),
                                                        load_with.repair, quantize));
  out->report["triangles"] = loaded->mesh.triangle_count();
  out->files.emplace_back("", std::move(packed.file));
  return Status::ok();
}

// The simplifier's options shared by the simplify and lods steps.
SimplifyStepOptions simplify_options(const nlohmann::json& o) {
  SimplifyStepOptions s;
  s.repair = o["repair"] == "repair";
  s.strict = o["repair"] == "strict";
  s.options.boundary_weight = o["boundary_weight"].get<double>();
  s.options.lock_border = o["lock_border"].get<bool>();
  s.options.max_normal_change_degrees = o["max_normal_change"].get<double>();
  s.options.permissive = o["permissive"].get<bool>();
  s.options.seam_release = o["seam_release"].get<double>();
  if (o.contains("placement")) {
    s.placement = o["placement"].get<std::string>();
    s.options.placement = s.placement == "optimal" ? Placement::kOptimal : Placement::kHalf;
    s.options.height_guard = o["height_guard"].get<bool>() || !o["height_guard_factor"].is_null();
    if (!o["height_guard_factor"].is_null())
      s.options.height_guard_factor = o["height_guard_factor"].get<double>();
    if (!o["ratio"].is_null()) s.options.target_ratio = o["ratio"].get<double>();
    if (!o["triangles"].is_null()) s.options.target_triangles = o["triangles"].get<uint64_t>();
    if (!o["error"].is_null()) s.options.max_error = o["error"].get<double>();
    s.quantize_bits = o["quantize"].get<int>();
    s.weights.normal = o["normal_weight"].get<double>();
    s.weights.texcoord = o["uv_weight"].get<double>();
    s.weights.color = o["color_weight"].get<double>();
    s.weights.tangent = o["tangent_weight"].get<double>();
  }
  return s;
}

// What a step asks InputMeshes to simplify, on a mesh input.
struct SimplifyAsk {
  LoadOptions load;
  SimplifyOptions options;
};

SimplifyAsk simplify_ask(const nlohmann::json& o) {
  SimplifyAsk ask;
  ask.load = load_options(o);
  ask.load.per_vertex_attributes = true;
  ask.options = simplify_options(o).options;
  ask.options.record_pm = true;
  return ask;
}

// Without strips_only, the strips follow a progressive mesh of their own
// (lodbake-strips' record_pm()).
std::optional<SimplifyAsk> strips_ask(const nlohmann::json& o) {
  if (o["strips_only"].get<bool>()) return std::nullopt;
  SimplifyAsk ask;
  ask.load = load_options(o);
  ask.load.per_vertex_attributes = true;
  ask.options = strips_pm_options(0);
  return ask;
}

std::optional<SimplifyAsk> step_ask(const StepPlan& step) {
  if (step.step == "simplify") return simplify_ask(step.options);
  if (step.step == "strips") return strips_ask(step.options);
  return std::nullopt;
}

Status run_simplify(const nlohmann::json& o, const std::string& input, const Bytes& bytes,
                    InputMeshes* meshes, StepResult* out) {
  SimplifyStepOptions request = simplify_options(o);
  if (request.options.height_guard && request.options.placement != Placement::kHalf)
    return Status(ErrorKind::kUsage, "steps.simplify: height_guard needs placement 'half'");
  if (is_asset(input, bytes)) {
    MetaSection meta = make_meta("lodbake-simplify");
    meta.options = pm_meta_options(request);
    std::map<uint32_t, MeshPm> pms;
    return build_over_asset(
        input, bytes, std::move(meta), load_options(o),
        [&](uint32_t scene_mesh, const TriangleMesh&) -> Result<MeshSections> {
          auto found = pms.find(scene_mesh);
          if (found == pms.end())
            return runtime_error("mesh " + std::to_string(scene_mesh) + " has no progressive mesh");
          return asset_pm_sections(request, found->second);
        },
        [&](const Scene& scene) -> Status {
          LODBAKE_ASSIGN_OR_RETURN(pms, asset_progressive_meshes(request, scene));
          return Status::ok();
        },
        out);
  }
  const SimplifyAsk ask = simplify_ask(o);
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, ask.load, &loaded, out));
  LODBAKE_ASSIGN_OR_RETURN(std::shared_ptr<const SimplifyResult> result,
                           meshes->simplified(loaded->mesh, ask.load, ask.options));
  LODBAKE_ASSIGN_OR_RETURN(
      Bytes file, pm_container_bytes(request, meta_input(input, *loaded), *result->pm, nullptr));
  out->report["triangles"] = result->mesh.triangle_count();
  out->report["splits"] = result->pm->splits.size();
  out->files.emplace_back("", std::move(file));
  return Status::ok();
}

// A chain by errors: one run per error, each what `lodbake-simplify IN -o
// OUT --error E` writes (a PM recorded to the largest error would not
// give the smaller ones: the engine's passes are scaled by the limit).
Status run_lods_by_error(const StepPlan& step, const std::string& input, const Bytes& bytes,
                         InputMeshes* meshes, StepResult* out) {
  const nlohmann::json& o = step.options;
  const std::vector<double> errors = o["errors"].get<std::vector<double>>();
  const std::string format = o["format"].get<std::string>();
  nlohmann::json triangles = nlohmann::json::array();
  if (is_scene_output("x." + format) && is_scene_source(input, bytes)) {
    LODBAKE_ASSIGN_OR_RETURN(Scene scene, read_input_asset(input, bytes, out));
    for (size_t level = 0; level < errors.size(); ++level) {
      SimplifyStepOptions request = simplify_options(o);
      SceneLodOptions options;
      options.simplify = request.options;
      options.simplify.max_error = errors[level];
      options.load.repair = request.repair;
      options.load.strict = request.strict;
      options.weights = request.weights;
      LODBAKE_ASSIGN_OR_RETURN(SceneLods lods, simplify_scene(scene, options));
      SceneWriteReport written;
      LODBAKE_ASSIGN_OR_RETURN(Bytes glb, write_scene_glb(lods.levels.at(0), &written));
      for (const std::string& w : written.warnings)
        out->warnings.push_back("level " + std::to_string(level) + ": " + w);
      uint64_t level_triangles = 0;
      for (const MeshLodReport& m : lods.meshes)
        level_triangles += m.lod_triangles.at(0);
      triangles.push_back(level_triangles);
      out->files.emplace_back("", std::move(glb));
    }
    out->report["triangles"] = triangles;
    return Status::ok();
  }
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_options(o), &loaded, out));
  for (size_t level = 0; level < errors.size(); ++level) {
    SimplifyStepOptions request = simplify_options(o);
    request.options.max_error = errors[level];
    LODBAKE_ASSIGN_OR_RETURN(SimplifyResult result, simplify(loaded->mesh, request.options));
    const std::string& path = step.outputs[level];
    if (drops_attributes(path, result.mesh))
      out->warnings.push_back("level " + std::to_string(level) +
                              ": this format cannot store the mesh's normals or texture "
                              "coordinates");
    LODBAKE_ASSIGN_OR_RETURN(Bytes file, write_mesh_for_path(path, result.mesh));
    triangles.push_back(result.mesh.triangle_count());
    out->files.emplace_back("", std::move(file));
  }
  out->report["triangles"] = triangles;
  return Status::ok();
}

Status run_lods(const StepPlan& step, const std::string& input, const Bytes& bytes,
                InputMeshes* meshes, StepResult* out) {
  const nlohmann::json& o = step.options;
  if (!o["errors"].is_null()) return run_lods_by_error(step, input, bytes, meshes, out);
  SimplifyStepOptions request = simplify_options(o);
  const std::vector<double> ratios = o["ratios"].get<std::vector<double>>();
  const std::string format = o["format"].get<std::string>();
  if (is_scene_output("x." + format) && is_scene_source(input, bytes)) {
    LODBAKE_ASSIGN_OR_RETURN(Scene scene, read_input_asset(input, bytes, out));
    SceneLodOptions options;
    options.simplify = request.options;
    options.load.repair = request.repair;
    options.load.strict = request.strict;
    options.weights = request.weights;
    options.ratios = ratios;
    LODBAKE_ASSIGN_OR_RETURN(SceneLods lods, simplify_scene(scene, options));
    for (size_t level = 0; level < lods.levels.size(); ++level) {
      SceneWriteReport written;
      LODBAKE_ASSIGN_OR_RETURN(Bytes glb, write_scene_glb(lods.levels[level], &written));
      for (const std::string& w : written.warnings)
        out->warnings.push_back("level " + std::to_string(level) + ": " + w);
      out->files.emplace_back("", std::move(glb));
    }
    return Status::ok();
  }
  LoadOptions load_with = load_options(o);
  load_with.per_vertex_attributes = true;
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_with, &loaded, out));
  request.options.target_ratio = *std::min_element(ratios.begin(), ratios.end());
  request.options.record_pm = true;
  LODBAKE_ASSIGN_OR_RETURN(SimplifyResult result, simplify(loaded->mesh, request.options));
  std::vector<uint64_t> targets;
  for (double r : ratios)
    targets.push_back(
        static_cast<uint64_t>(r * static_cast<double>(loaded->mesh.triangle_count())));
  LODBAKE_ASSIGN_OR_RETURN(std::vector<TriangleMesh> lods, extract_lods(*result.pm, targets));
  nlohmann::json triangles = nlohmann::json::array();
  for (size_t level = 0; level < lods.size(); ++level) {
    const std::string& path = step.outputs[level];
    if (drops_attributes(path, lods[level]))
      out->warnings.push_back("level " + std::to_string(level) +
                              ": this format cannot store the mesh's normals or texture "
                              "coordinates");
    LODBAKE_ASSIGN_OR_RETURN(Bytes file, write_mesh_for_path(path, lods[level]));
    triangles.push_back(lods[level].triangle_count());
    out->files.emplace_back("", std::move(file));
  }
  out->report["triangles"] = triangles;
  return Status::ok();
}

Status run_hierarchy(const nlohmann::json& o, const std::string& input, const Bytes& bytes,
                     InputMeshes* meshes, StepResult* out) {
  HierarchyStepOptions request;
  request.sections.clear();
  for (const nlohmann::json& s : o["sections"])
    request.sections += (request.sections.empty() ? "" : ",") + s.get<std::string>();
  LODBAKE_RETURN_IF_ERROR(parse_hierarchy_sections(&request));
  request.repair = o["repair"] == "repair";
  request.strict = o["repair"] == "strict";
  request.options.boundary_weight = o["boundary_weight"].get<double>();
  request.options.max_normal_change_degrees = o["max_normal_change"].get<double>();
  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = hierarchy_meta_options(request);
  if (is_asset(input, bytes)) {
    // As lodbake-hierarchy: the hierarchy's progressive mesh (with DAGE or
    // VTRE) carries the asset's wedges.
    std::map<uint32_t, MeshCornerWedges> corners;
    return build_over_asset(
        input, bytes, std::move(meta), load_options(o),
        [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
          LODBAKE_ASSIGN_OR_RETURN(HierarchyBuilt b, build_hierarchy_sections(request, mesh));
          return hierarchy_mesh_sections(std::move(b), corners, scene_mesh, mesh);
        },
        [&](const Scene& scene) -> Status {
          if (!request.dage && !request.vtre) return Status::ok();
          LODBAKE_ASSIGN_OR_RETURN(corners, asset_corner_wedges(request, scene));
          return Status::ok();
        },
        out);
  }
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_options(o), &loaded, out));
  // The hierarchy is of positions only (as lodbake-hierarchy): a copy
  // without the attributes when there are any.
  const TriangleMesh* mesh = &loaded->mesh;
  TriangleMesh positions;
  if (mesh->normals.present() || mesh->texcoords.present()) {
    positions.positions = mesh->positions;
    positions.triangles = mesh->triangles;
    mesh = &positions;
  }
  LODBAKE_ASSIGN_OR_RETURN(HierarchyBuilt built, build_hierarchy_sections(request, *mesh));
  meta.input = meta_input(input, *loaded);
  meta.counts = built.counts;
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  for (HierarchySection& s : built.sections)
    LODBAKE_RETURN_IF_ERROR(writer.add_known_section(s.tag, std::move(s.bytes)));
  LODBAKE_ASSIGN_OR_RETURN(Bytes file, writer.finish());
  out->report["nodes"] = built.shape.nodes;
  out->files.emplace_back("", std::move(file));
  return Status::ok();
}

Status run_fan(const nlohmann::json& o, const std::string& input, const Bytes& bytes,
               InputMeshes* meshes, StepResult* out) {
  FanStepOptions request;
  request.repair = o["repair"] == "repair";
  request.strict = o["repair"] == "strict";
  request.options.degree_weight = o["degree_weight"].get<double>();
  request.options.boundary_weight = o["boundary_weight"].get<double>();
  request.options.max_normal_change_degrees = o["max_normal_change"].get<double>();
  if (!o["ratio"].is_null()) request.options.target_ratio = o["ratio"].get<double>();
  if (!o["vertices"].is_null()) request.options.target_vertices = o["vertices"].get<uint64_t>();
  if (!o["error"].is_null()) request.options.max_error = o["error"].get<double>();
  if (is_asset(input, bytes)) {
    // Every front carries the asset's wedges (WEDG).
    std::map<uint32_t, MeshCornerWedges> corners;
    return build_over_asset(
        input, bytes, fan_meta(request), load_options(o),
        [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
          LODBAKE_ASSIGN_OR_RETURN(FanBuilt b, build_fan(request.options, mesh));
          return fan_asset_sections(std::move(b), corners, scene_mesh, mesh);
        },
        [&](const Scene& scene) -> Status {
          LODBAKE_ASSIGN_OR_RETURN(corners, fan_asset_corners(request, scene));
          return Status::ok();
        },
        out);
  }
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_options(o), &loaded, out));
  LODBAKE_ASSIGN_OR_RETURN(FanBuilt built, build_fan(request.options, loaded->mesh));
  MetaSection meta = fan_meta(request);
  meta.input = meta_input(input, *loaded);
  meta.counts = built.counts;
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kBaseTag, std::move(built.base)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kFanhTag, std::move(built.fanh)));
  LODBAKE_ASSIGN_OR_RETURN(Bytes file, writer.finish());
  out->report["internal_nodes"] = built.stats.internal_nodes;
  out->files.emplace_back("", std::move(file));
  return Status::ok();
}

Status run_strips(const nlohmann::json& o, const std::string& input, const Bytes& bytes,
                  InputMeshes* meshes, StepResult* out) {
  StripsStepOptions request;
  request.strips_only = o["strips_only"].get<bool>();
  request.repair = o["repair"] == "repair";
  request.strict = o["repair"] == "strict";
  if (is_asset(input, bytes)) {
    // As lodbake-strips: the progressive mesh under the graph carries the
    // asset's wedges.
    AssetCorners corners;
    return build_over_asset(
        input, bytes, strips_meta(request), load_options(o),
        [&](uint32_t scene_mesh, const TriangleMesh& mesh) {
          return strips_mesh_sections(request, corners, scene_mesh, mesh);
        },
        [&](const Scene& scene) -> Status {
          if (request.strips_only) return Status::ok();
          LODBAKE_ASSIGN_OR_RETURN(corners,
                                   read_asset_corners(scene, request.repair, request.strict));
          return Status::ok();
        },
        out);
  }
  LoadOptions load_with = load_options(o);
  std::optional<SimplifyAsk> ask = strips_ask(o);
  if (ask) load_with = ask->load;
  std::shared_ptr<const LoadedMesh> loaded;
  LODBAKE_RETURN_IF_ERROR(load(meshes, input, bytes, load_with, &loaded, out));
  StripsInput in;
  in.meta = meta_input(input, *loaded);
  if (request.strips_only) {
    in.mesh = loaded->mesh;
  } else {
    LODBAKE_ASSIGN_OR_RETURN(std::shared_ptr<const SimplifyResult> simplified,
                             meshes->simplified(loaded->mesh, ask->load, ask->options));
    if (!simplified->pm) return runtime_error("the simplification recorded no progressive mesh");
    in.pm = std::shared_ptr<const ProgressiveMesh>(simplified, &*simplified->pm);
  }
  LODBAKE_ASSIGN_OR_RETURN(StripsBuilt built, build_strips(request, in));
  out->report["strips"] = built.strip_stats.strips;
  LODBAKE_ASSIGN_OR_RETURN(Bytes file, strips_container(request, in, std::move(built)));
  out->files.emplace_back("", std::move(file));
  return Status::ok();
}

// lodbake-pack's repack of the earlier steps' containers, with its META
// options (tools/pack/main.cpp).
// The files are taken from `earlier`, not copied: a large mesh's four
// containers are the bake's largest buffers.
Status run_package(const StepPlan& step, std::map<std::string, std::vector<Bytes>>* earlier,
                   StepResult* out) {
  const nlohmann::json& o = step.options;
  std::vector<PackInput> inputs;
  for (const nlohmann::json& from : o["from"]) {
    auto found = earlier ? earlier->find(from.get<std::string>())
                         : std::map<std::string, std::vector<Bytes>>::iterator();
    if (!earlier || found == earlier->end() || found->second.empty())
      return runtime_error("steps.package: step '" + from.get<std::string>() + "' made no file");
    inputs.push_back({from.get<std::string>(), std::move(found->second.front())});
  }
  RepackOptions options;
  options.quantize_bits = o["quantize"].get<int>();
  options.error_bits = o["error_bits"].get<int>();
  options.compact = o["compact"].get<bool>();
  options.draco = o["draco"].get<bool>();
  options.draco_options.quantization_bits = o["qp"].get<int>();
  options.draco_options.compression_level = o["cl"].get<int>();
  nlohmann::json meta_options = {
      {"draco", options.draco},
      {"compact", options.compact},
      {"quantize_bits", options.quantize_bits == 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(options.quantize_bits)},
      {"drop", options.drop},
      {"keep", options.keep}};
  if (options.draco)
    meta_options["draco_options"] = {{"qp", o["qp"].get<int>()}, {"cl", o["cl"].get<int>()}};
  if (options.error_bits != 0) meta_options["error_bits"] = options.error_bits;
  size_t failed = inputs.size();
  LODBAKE_ASSIGN_OR_RETURN(PackResult packed,
                           repack_containers(std::move(inputs), options, meta_options, &failed));
  out->report["sections"] = packed.sections.size();
  out->files.emplace_back("", std::move(packed.file));
  return Status::ok();
}

}  // namespace

InputMeshes::InputMeshes(const std::vector<StepPlan>& steps) {
  for (const StepPlan& step : steps) {
    if (step.step != "package") ++loads_left_;
    const std::optional<SimplifyAsk> ask = step_ask(step);
    const std::string options_key = ask ? simplify_key(ask->options) : "";
    if (options_key.empty()) continue;
    std::unique_ptr<Simplification>& slot =
        simplifications_[load_key(ask->load) + " " + options_key];
    if (!slot) slot = std::make_unique<Simplification>();
    ++slot->askers;
  }
}

Result<std::shared_ptr<const LoadedMesh>> InputMeshes::parse(const std::string& input,
                                                             const Bytes& bytes) {
  std::lock_guard<std::mutex> lock(parse_mutex_);
  if (!parsed_status_.is_ok()) return parsed_status_;
  if (!parsed_) {
    // First, or asked for once more than planned after the release.
    auto parsed = std::make_shared<LoadedMesh>();
    parsed_status_ = parse_mesh_bytes(input, bytes, parsed.get());
    if (!parsed_status_.is_ok()) return parsed_status_;
    per_corner_ = has_per_corner_attributes(parsed->mesh);
    parsed_ = std::move(parsed);
  }
  return parsed_;
}

Result<std::shared_ptr<const LoadedMesh>> InputMeshes::load(const std::string& input,
                                                            const Bytes& bytes,
                                                            const LoadOptions& options) {
  // Parsed once; checked and repaired once per set of the options a step
  // can vary. The seam split changes nothing on a mesh without per-corner
  // attributes (a scan), so there the steps with and without it share one.
  LODBAKE_ASSIGN_OR_RETURN(std::shared_ptr<const LoadedMesh> parsed, parse(input, bytes));
  const bool split = options.per_vertex_attributes && per_corner_;
  const std::string key = std::to_string(options.repair) + std::to_string(options.strict) +
                          std::to_string(split) + std::to_string(options.drop_unreferenced);
  Entry* entry = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::unique_ptr<Entry>& slot = entries_[key];
    if (!slot) slot = std::make_unique<Entry>();
    entry = slot.get();
  }
  std::call_once(entry->once, [&] {
    auto prepared = std::make_shared<LoadedMesh>(*parsed);
    entry->status = prepare_mesh(options, prepared.get());
    entry->loaded = std::move(prepared);
  });
  parsed.reset();
  {
    // Every step has its mesh: the parse is of no more use.
    std::lock_guard<std::mutex> lock(mutex_);
    if (loads_left_ > 0 && --loads_left_ == 0) {
      std::lock_guard<std::mutex> parse_lock(parse_mutex_);
      parsed_.reset();
    }
  }
  if (!entry->status.is_ok()) return entry->status;
  return entry->loaded;
}

Result<std::shared_ptr<const SimplifyResult>> InputMeshes::simplified(
    const TriangleMesh& mesh, const LoadOptions& load_options, const SimplifyOptions& options) {
  auto run = [&]() -> Result<std::shared_ptr<const SimplifyResult>> {
    LODBAKE_ASSIGN_OR_RETURN(SimplifyResult result, simplify(mesh, options));
    return std::make_shared<const SimplifyResult>(std::move(result));
  };
  const std::string options_key = simplify_key(options);
  if (options_key.empty()) return run();
  Simplification* entry = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::unique_ptr<Simplification>& slot =
        simplifications_[load_key(load_options) + " " + options_key];
    if (!slot) slot = std::make_unique<Simplification>();
    entry = slot.get();
  }
  // The simplifier's parallel loops are isolated (lib/core/parallel.cpp):
  // a thread waiting in them never takes up another step, which could ask
  // for this same result inside this call_once.
  std::call_once(entry->once, [&] {
    Result<std::shared_ptr<const SimplifyResult>> made = run();
    if (made.is_ok()) {
      entry->result = std::move(made).value();
    } else {
      entry->status = made.status();
    }
  });
  if (!entry->status.is_ok()) return entry->status;
  std::shared_ptr<const SimplifyResult> result;
  {
    // The last step that asks takes the only reference left: the result
    // goes with its step, not with the input.
    std::lock_guard<std::mutex> lock(mutex_);
    result = entry->result;
    if (entry->askers > 0 && --entry->askers == 0) entry->result.reset();
  }
  if (!result) return run();  // asked once more than planned, after its release
  return result;
}

Result<StepResult> run_bake_step(const StepPlan& step, const std::string& input, const Bytes& bytes,
                                 std::map<std::string, std::vector<Bytes>>* earlier,
                                 InputMeshes* meshes) {
  StepResult out;
  const nlohmann::json& o = step.options;
  Status status = Status::ok();
  if (step.step == "pack") {
    status = run_pack(o, input, bytes, meshes, &out);
  } else if (step.step == "simplify") {
    status = run_simplify(o, input, bytes, meshes, &out);
  } else if (step.step == "lods") {
    status = run_lods(step, input, bytes, meshes, &out);
  } else if (step.step == "hierarchy") {
    status = run_hierarchy(o, input, bytes, meshes, &out);
  } else if (step.step == "fan") {
    status = run_fan(o, input, bytes, meshes, &out);
  } else if (step.step == "strips") {
    status = run_strips(o, input, bytes, meshes, &out);
  } else if (step.step == "package") {
    status = run_package(step, earlier, &out);
  } else {
    status = Status(ErrorKind::kUsage, "unknown step '" + step.step + "'");
  }
  LODBAKE_RETURN_IF_ERROR(status);
  if (out.files.size() != step.outputs.size())
    return runtime_error("step " + step.step + " made " + std::to_string(out.files.size()) +
                         " files for " + std::to_string(step.outputs.size()) + " outputs");
  for (size_t i = 0; i < out.files.size(); ++i)
    out.files[i].first = step.outputs[i];
  return out;
}

}  // namespace lodbake
