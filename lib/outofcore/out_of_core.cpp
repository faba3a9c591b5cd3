// Out-of-core simplification by spatial blocks with locked borders, then a
// merge pass: the scheme of Hoppe's "Smooth view-dependent level-of-detail
// control" for terrains (1998) and of Cignoni et al.'s external-memory
// simplification (2003), with the blocks simplified by the in-core QEM
// engine. Chosen over Lindstrom's out-of-core clustering (OoCS, 2000):
// clustering snaps every vertex to a grid cell's representative, whose
// Hausdorff error is bounded by the cell size, not by the quadric order the
// in-core engine follows; edge collapses in the blocks and the merge keep
// that order almost everywhere (docs/simplify.md, docs/lab/out-of-core.md).
#include "lib/outofcore/out_of_core.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "formats/support/file_io.h"
#include "lib/meshio/file_name.h"
#include "lib/meshio/obj_stream_reader.h"
#include "lib/meshio/ply_stream_reader.h"
#include "lib/outofcore/block_mesh.h"
#include "lib/outofcore/block_partition.h"

namespace lodbake {
namespace {

namespace fs = std::filesystem;

std::string numbered(const std::string& work, const char* stem, uint32_t block, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%04u.%s", stem, block, ext);
  return (fs::path(work) / name).string();
}

std::string block_scratch_path(const std::string& work, uint32_t block) {
  return numbered(work, "block", block, "tris");
}

// The engine's options as plan.json stores them (callbacks and threads are
// the running process's own).
nlohmann::json options_json(const SimplifyOptions& o) {
  nlohmann::json j = {{"placement", o.placement == Placement::kHalf ? "half" : "optimal"},
                      {"boundary_weight", o.boundary_weight},
                      {"lock_border", o.lock_border},
                      {"max_normal_change_degrees", o.max_normal_change_degrees},
                      {"height_guard", o.height_guard},
                      {"height_guard_factor", o.height_guard_factor}};
  j["max_error"] = o.max_error ? nlohmann::json(*o.max_error) : nlohmann::json(nullptr);
  return j;
}

SimplifyOptions options_from_json(const nlohmann::json& j) {
  SimplifyOptions o;
  o.placement =
      j.at("placement").get<std::string>() == "half" ? Placement::kHalf : Placement::kOptimal;
  o.boundary_weight = j.at("boundary_weight").get<double>();
  o.lock_border = j.at("lock_border").get<bool>();
  o.max_normal_change_degrees = j.at("max_normal_change_degrees").get<double>();
  o.height_guard = j.at("height_guard").get<bool>();
  o.height_guard_factor = j.at("height_guard_factor").get<double>();
  if (!j.at("max_error").is_null()) o.max_error = j.at("max_error").get<double>();
  return o;
}

// The diagonal of the box of the mesh's vertices, as the engine measures it
// (float bounds, double sum), so that an error relative to the input's
// diagonal can be handed to a pass on a part of it.
double diagonal_of(const std::vector<Vec3f>& positions) {
  if (positions.empty()) return 0;
  Vec3f lo = positions[0], hi = positions[0];
  for (const Vec3f& p : positions)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  double d = 0;
  for (int k = 0; k < 3; ++k)
    d += (double{hi[k]} - lo[k]) * (double{hi[k]} - lo[k]);
  return std::sqrt(d);
}

// max_error is relative to the input's diagonal; a pass over a part of it
// measures against the part's own.
void scale_max_error(const OutOfCorePlan& plan, double part_diagonal, SimplifyOptions* o) {
  if (o->max_error && part_diagonal > 0) *o->max_error *= plan.diagonal / part_diagonal;
}

Status append_file(const std::string& path, const std::vector<Triangle>& triangles) {
  std::ofstream out(path, std::ios::binary | std::ios::app);
  out.write(reinterpret_cast<const char*>(triangles.data()),
            static_cast<std::streamsize>(triangles.size() * sizeof(Triangle)));
  if (!out) return io_error("cannot write the work file '" + path + "'");
  return Status::ok();
}

// The split's body; split_input() removes what it wrote when this fails.
Result<OutOfCorePlan> split(const std::string& input, const std::string& work,
                            const OutOfCoreOptions& options, const StageProgress& progress) {
  std::error_code error;
  const uint64_t size = fs::file_size(input, error);
  if (error) return io_error("cannot read: " + error.message());
  std::ifstream in(input, std::ios::binary);
  if (!in) return io_error("cannot open for reading");
  char magic[4] = {0, 0, 0, 0};
  in.read(magic, 4);
  const bool is_ply =
      in.gcount() == 4 && std::string(magic, 3) == "ply" && (magic[3] == '\n' || magic[3] == '\r');
  // OBJ has no magic: its extension decides, as in core (mesh_import.cpp).
  if (!is_ply && lower_extension(input) != "obj")
    return unsupported("--memory-limit reads PLY (binary or ASCII) and OBJ files only");
  std::unique_ptr<PlyStreamReader> ply;
  std::unique_ptr<ObjStreamReader> obj;
  if (is_ply) {
    LODBAKE_ASSIGN_OR_RETURN(ply, PlyStreamReader::open(&in, size));
  } else {
    LODBAKE_ASSIGN_OR_RETURN(obj, ObjStreamReader::open(&in, size));
  }
  OutOfCorePlan plan;
  plan.memory_limit = options.memory_limit;
  plan.simplify = options.simplify;
  const uint64_t limit = options.memory_limit;
  // What the arrays that grow with a block may take: the limit less the
  // program itself.
  const uint64_t usable = limit - std::min(limit / 2, kProgramBytes);
  auto too_many_vertices = [&](uint64_t count) {
    return runtime_error("its " + std::to_string(count) + " vertices need " +
                         std::to_string(count * sizeof(Vec3f)) +
                         " bytes, more than half of --memory-limit");
  };

  // Pass 1: positions and their box. The positions are the one array over
  // the whole input.
  std::vector<Vec3f> positions;
  if (ply) {
    // The header's count (plan_ply() checked that the body can hold it).
    plan.input_vertices = ply->vertex_count();
    if (plan.input_vertices * sizeof(Vec3f) > limit / 2)
      return too_many_vertices(plan.input_vertices);
    positions.resize(plan.input_vertices);
    LODBAKE_RETURN_IF_ERROR(ply->for_each_vertex([&](uint64_t i, const float* xyz) {
      positions[i] = {xyz[0], xyz[1], xyz[2]};
    }));
  } else {
    // No count ahead: stop as soon as the vertices read pass the limit.
    LODBAKE_RETURN_IF_ERROR(obj->for_each_vertex([&](uint64_t, const float* xyz) -> Status {
      const uint64_t most = limit / 2 / sizeof(Vec3f);
      if (positions.size() + 1 > most) return too_many_vertices(positions.size() + 1);
      // Grown by hand: the block never passes the half of the limit the
      // positions may take (push_back's doubling could reserve twice it).
      if (positions.size() == positions.capacity())
        positions.reserve(static_cast<size_t>(
            std::min<uint64_t>(std::max<uint64_t>(2 * positions.capacity(), 1024), most)));
      positions.push_back({xyz[0], xyz[1], xyz[2]});
      return Status::ok();
    }));
    plan.input_vertices = positions.size();
  }
  const uint64_t faces = std::max<uint64_t>(ply ? ply->face_count() : obj->face_count(), 1);
  auto for_each_triangle =
      [&](const std::function<Status(uint64_t, const uint32_t*)>& triangle) -> Status {
    return ply ? ply->for_each_triangle(triangle) : obj->for_each_triangle(positions, triangle);
  };
  if (progress) progress(0.1);
  Vec3f lo{0, 0, 0}, hi{0, 0, 0};
  if (!positions.empty()) lo = hi = positions[0];
  for (const Vec3f& p : positions)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }

  // Pass 2: triangles per fine cell, and the referenced vertices (the
  // diagonal is theirs, as in core once unreferenced vertices are dropped).
  BlockGrid grid = make_block_grid(lo, hi, kFineGridResolution);
  std::vector<uint64_t> counts(grid.cell_count(), 0);
  std::vector<bool> referenced(plan.input_vertices, false);
  LODBAKE_RETURN_IF_ERROR(for_each_triangle([&](uint64_t f, const uint32_t* t) -> Status {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++plan.dropped_degenerate;
      return Status::ok();
    }
    ++counts[grid.cell_of(positions[t[0]], positions[t[1]], positions[t[2]])];
    ++plan.input_triangles;
    for (int k = 0; k < 3; ++k)
      referenced[t[k]] = true;
    if (progress && f % 1000000 == 0) progress(0.1 + 0.3 * static_cast<double>(f) / faces);
    return Status::ok();
  }));
  if (plan.input_triangles == 0) return invalid_input("the mesh has no triangles");
  {
    Vec3f rlo{0, 0, 0}, rhi{0, 0, 0};
    bool first = true;
    for (size_t v = 0; v < positions.size(); ++v) {
      if (!referenced[v]) continue;
      ++plan.referenced_vertices;
      if (first) rlo = rhi = positions[v];
      first = false;
      for (int k = 0; k < 3; ++k) {
        rlo[k] = std::min(rlo[k], positions[v][k]);
        rhi[k] = std::max(rhi[k], positions[v][k]);
      }
    }
    double d = 0;
    for (int k = 0; k < 3; ++k)
      d += (double{rhi[k]} - rlo[k]) * (double{rhi[k]} - rlo[k]);
    plan.diagonal = std::sqrt(d);
  }

  // Targets: the final one as in core, and the blocks' one.
  const SimplifyOptions& s = options.simplify;
  const uint64_t total = plan.input_triangles;
  if (s.target_triangles || s.target_ratio) {
    uint64_t target = s.target_triangles.value_or(0);
    if (s.target_ratio) {
      const auto by_ratio =
          static_cast<uint64_t>(std::floor(*s.target_ratio * static_cast<double>(total)));
      if (!s.target_triangles || by_ratio > target) target = by_ratio;
    }
    plan.final_triangles = target;
    const uint64_t merge_capacity = usable / kEngineBytesPerTriangle;
    if (target > merge_capacity)
      return runtime_error("the target of " + std::to_string(target) +
                           " triangles needs more than --memory-limit in the final pass (at " +
                           std::to_string(kEngineBytesPerTriangle) +
                           " bytes a triangle); raise the limit or lower the target");
    const double ratio = static_cast<double>(target) / static_cast<double>(total);
    double block_ratio = std::min(1.0, ratio * options.block_ratio_factor);
    // The stitched mesh must fit the final pass; borders are kept whole, so
    // leave a quarter of the capacity for them.
    block_ratio = std::min(block_ratio,
                           0.75 * static_cast<double>(merge_capacity) / static_cast<double>(total));
    plan.block_ratio = std::max(block_ratio, ratio);
  }

  plan.block_budget = std::max<uint64_t>(usable / kEngineBytesPerTriangle, 1);
  partition_blocks(counts, plan.block_budget, &grid);
  if (grid.block_count > kMaxBlocks)
    return runtime_error("--memory-limit would cut the mesh into " +
                         std::to_string(grid.block_count) + " blocks, more than " +
                         std::to_string(kMaxBlocks) + "; raise the limit");
  plan.block_triangles.assign(grid.block_count, 0);
  for (size_t c = 0; c < counts.size(); ++c)
    if (grid.cell_block[c] != kNoBlock) plan.block_triangles[grid.cell_block[c]] += counts[c];
  counts = std::vector<uint64_t>();
  referenced = std::vector<bool>();

  // Pass 3: each triangle to its block's scratch file, through one buffer
  // per block that together take an eighth of the limit.
  const uint64_t per_block =
      std::clamp<uint64_t>(limit / 8 / sizeof(Triangle) / grid.block_count, 1024, 1 << 16);
  std::vector<std::vector<Triangle>> buffers(grid.block_count);
  auto distribute = [&](uint64_t f, const uint32_t* t) -> Status {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return Status::ok();
    const uint32_t b = grid.block_of(positions[t[0]], positions[t[1]], positions[t[2]]);
    buffers[b].push_back({t[0], t[1], t[2]});
    if (buffers[b].size() >= per_block) {
      LODBAKE_RETURN_IF_ERROR(append_file(block_scratch_path(work, b), buffers[b]));
      buffers[b].clear();
    }
    if (progress && f % 1000000 == 0) progress(0.4 + 0.4 * static_cast<double>(f) / faces);
    return Status::ok();
  };
  LODBAKE_RETURN_IF_ERROR(for_each_triangle(distribute));
  for (uint32_t b = 0; b < grid.block_count; ++b) {
    LODBAKE_RETURN_IF_ERROR(append_file(block_scratch_path(work, b), buffers[b]));
    buffers[b] = std::vector<Triangle>();
  }

  // Each block's triangles on its own vertices, with their input ids.
  uint64_t largest_block = 0;
  for (uint32_t b = 0; b < grid.block_count; ++b) {
    const std::string scratch = block_scratch_path(work, b);
    LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(scratch));
    std::vector<Triangle> triangles(bytes.size() / sizeof(Triangle));
    std::memcpy(triangles.data(), bytes.data(), triangles.size() * sizeof(Triangle));
    bytes = Bytes();
    BlockMesh block;
    for (const Triangle& t : triangles)
      block.ids.insert(block.ids.end(), t.begin(), t.end());
    std::sort(block.ids.begin(), block.ids.end());
    block.ids.erase(std::unique(block.ids.begin(), block.ids.end()), block.ids.end());
    block.ids.shrink_to_fit();
    block.positions.reserve(block.ids.size());
    for (uint32_t id : block.ids)
      block.positions.push_back(positions[id]);
    for (Triangle& t : triangles)
      for (uint32_t& v : t)
        v = static_cast<uint32_t>(std::lower_bound(block.ids.begin(), block.ids.end(), v) -
                                  block.ids.begin());
    block.triangles = std::move(triangles);
    split_vertex_fans(&block);
    largest_block = std::max<uint64_t>(largest_block, block.triangles.size());
    LODBAKE_RETURN_IF_ERROR(write_file_atomic(block_input_path(work, b), encode_block(block)));
    fs::remove(scratch, error);
    if (progress) progress(0.8 + 0.2 * (b + 1) / grid.block_count);
  }
  // What each stage holds at its peak: the split its positions, buffers
  // and one block being written; a block and the merge the engine's arrays.
  const uint64_t split_peak = plan.input_vertices * sizeof(Vec3f) +
                              per_block * sizeof(Triangle) * grid.block_count + largest_block * 40;
  const uint64_t merge_triangles =
      plan.block_ratio
          ? static_cast<uint64_t>(std::ceil(*plan.block_ratio * static_cast<double>(total)))
          : total;
  plan.peak_estimate = std::max({split_peak, largest_block * kEngineBytesPerTriangle,
                                 merge_triangles * kEngineBytesPerTriangle});
  return plan;
}

std::string plan_text(const OutOfCorePlan& plan) {
  nlohmann::json j = {{"version", 1},
                      {"memory_limit", plan.memory_limit},
                      {"input_vertices", plan.input_vertices},
                      {"referenced_vertices", plan.referenced_vertices},
                      {"input_triangles", plan.input_triangles},
                      {"dropped_degenerate", plan.dropped_degenerate},
                      {"diagonal", plan.diagonal},
                      {"block_budget", plan.block_budget},
                      {"block_triangles", plan.block_triangles},
                      {"peak_estimate", plan.peak_estimate},
                      {"options", options_json(plan.simplify)}};
  j["block_ratio"] = plan.block_ratio ? nlohmann::json(*plan.block_ratio) : nlohmann::json(nullptr);
  j["final_triangles"] =
      plan.final_triangles ? nlohmann::json(*plan.final_triangles) : nlohmann::json(nullptr);
  return j.dump(1) + "\n";
}

}  // namespace

std::string plan_path(const std::string& work) {
  return (fs::path(work) / "plan.json").string();
}
std::string block_input_path(const std::string& work, uint32_t block) {
  return numbered(work, "block", block, "in");
}
std::string block_output_path(const std::string& work, uint32_t block) {
  return numbered(work, "block", block, "out");
}

void remove_work_files(const std::string& work) {
  std::error_code error;
  std::vector<fs::path> ours;
  for (const fs::directory_entry& entry : fs::directory_iterator(work, error)) {
    const std::string name = entry.path().filename().string();
    const bool block = name.rfind("block_", 0) == 0 &&
                       (entry.path().extension() == ".in" || entry.path().extension() == ".out" ||
                        entry.path().extension() == ".tris");
    if (block || name == "plan.json") ours.push_back(entry.path());
  }
  for (const fs::path& p : ours)
    fs::remove(p, error);
  if (fs::is_empty(work, error)) fs::remove(work, error);
}

Result<OutOfCorePlan> split_input(const std::string& input, const std::string& work,
                                  const OutOfCoreOptions& options, const StageProgress& progress) {
  if (options.simplify.record_pm)
    return unsupported("an out-of-core run records no progressive mesh");
  Result<OutOfCorePlan> plan = [&]() -> Result<OutOfCorePlan> {
    try {
      LODBAKE_ASSIGN_OR_RETURN(OutOfCorePlan p, split(input, work, options, progress));
      LODBAKE_RETURN_IF_ERROR(write_file_atomic(plan_path(work), plan_text(p)));
      return p;
    } catch (const std::bad_alloc&) {
      return runtime_error("out of memory while cutting the mesh into blocks");
    }
  }();
  if (!plan.is_ok()) {
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(work, error)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("block_", 0) == 0 || name == "plan.json") fs::remove(entry.path(), error);
    }
  }
  return plan;
}

Result<OutOfCorePlan> read_plan(const std::string& work) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(plan_path(work), 1 << 26));
  try {
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end());
    if (j.at("version").get<int>() != 1) return unsupported("plan.json of another version");
    OutOfCorePlan plan;
    plan.memory_limit = j.at("memory_limit").get<uint64_t>();
    plan.input_vertices = j.at("input_vertices").get<uint64_t>();
    plan.referenced_vertices = j.at("referenced_vertices").get<uint64_t>();
    plan.input_triangles = j.at("input_triangles").get<uint64_t>();
    plan.dropped_degenerate = j.at("dropped_degenerate").get<uint64_t>();
    plan.diagonal = j.at("diagonal").get<double>();
    plan.block_budget = j.at("block_budget").get<uint64_t>();
    plan.block_triangles = j.at("block_triangles").get<std::vector<uint64_t>>();
    plan.peak_estimate = j.at("peak_estimate").get<uint64_t>();
    plan.simplify = options_from_json(j.at("options"));
    if (!j.at("block_ratio").is_null()) plan.block_ratio = j.at("block_ratio").get<double>();
    if (!j.at("final_triangles").is_null())
      plan.final_triangles = j.at("final_triangles").get<uint64_t>();
    if (plan.block_triangles.empty() || plan.block_triangles.size() > kMaxBlocks ||
        (plan.block_ratio && !(*plan.block_ratio > 0 && *plan.block_ratio <= 1)))
      return invalid_input("plan.json is inconsistent");
    return plan;
  } catch (const nlohmann::json::exception&) {
    return invalid_input("plan.json is not a plan written by the split stage");
  }
}

Status simplify_block(const std::string& work, const OutOfCorePlan& plan, uint32_t block,
                      unsigned threads) {
  if (block >= plan.block_count())
    return invalid_input("no block " + std::to_string(block) + " (the plan has " +
                         std::to_string(plan.block_count()) + ")");
  try {
    LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(block_input_path(work, block)));
    LODBAKE_ASSIGN_OR_RETURN(BlockMesh in, decode_block(bytes));
    bytes = Bytes();
    TriangleMesh mesh;
    mesh.positions = std::move(in.positions);
    mesh.triangles = std::move(in.triangles);
    SimplifyOptions options = plan.simplify;
    // The cut's edges are the block's borders: locked with a band around
    // them (border_band()), the neighbours meet there again. The input's
    // own borders are locked too; the merge frees them.
    options.lock_border = true;
    options.locked_vertices = border_band(mesh.positions.size(), mesh.triangles);
    options.threads = threads;
    // The ratio applies to what the block may simplify: the triangles the
    // band holds whole stay on top, so that a small block is not simplified
    // past the ratio inside to make up for its border.
    options.target_ratio.reset();
    options.target_triangles.reset();
    if (plan.block_ratio) {
      uint64_t fixed = 0;
      for (const Triangle& t : mesh.triangles)
        fixed += options.locked_vertices[t[0]] & options.locked_vertices[t[1]] &
                 options.locked_vertices[t[2]];
      options.target_triangles =
          fixed + static_cast<uint64_t>(std::floor(
                      *plan.block_ratio * static_cast<double>(mesh.triangles.size() - fixed)));
    }
    scale_max_error(plan, diagonal_of(mesh.positions), &options);
    Result<SimplifyResult> simplified = simplify(std::move(mesh), options);
    if (!simplified.is_ok())
      return Status(simplified.status().kind(),
                    "block " + std::to_string(block) + ": " + simplified.status().message());
    SimplifyResult& result = simplified.value();
    BlockMesh out;
    out.ids.reserve(result.vertex_sources.size());
    for (uint32_t source : result.vertex_sources)
      out.ids.push_back(in.ids[source]);
    out.positions = std::move(result.mesh.positions);
    out.triangles = std::move(result.mesh.triangles);
    return write_file_atomic(block_output_path(work, block), encode_block(out));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while simplifying block " + std::to_string(block));
  }
}

Result<MergeResult> merge_blocks(const std::string& work, const OutOfCorePlan& plan,
                                 unsigned threads, const StageProgress& progress) {
  try {
    BlockStitcher stitcher;
    for (uint32_t b = 0; b < plan.block_count(); ++b) {
      Result<Bytes> bytes = read_file(block_output_path(work, b));
      if (!bytes.is_ok())
        return Status(bytes.status().kind(), "block " + std::to_string(b) +
                                                 " is not simplified yet (" +
                                                 bytes.status().message() + ")");
      Result<BlockMesh> block = decode_block(bytes.value());
      if (!block.is_ok())
        return invalid_input("block " + std::to_string(b) + ": " + block.status().message());
      LODBAKE_RETURN_IF_ERROR(stitcher.add(block.value()));
    }
    LODBAKE_ASSIGN_OR_RETURN(TriangleMesh stitched, stitcher.finish());
    MergeResult merged;
    merged.stitched_triangles = stitched.triangles.size();
    SimplifyOptions options = plan.simplify;
    options.threads = threads;
    options.target_triangles = plan.final_triangles;
    options.target_ratio.reset();
    scale_max_error(plan, diagonal_of(stitched.positions), &options);
    if (progress) options.progress = progress;
    Result<SimplifyResult> simplified = simplify(std::move(stitched), options);
    if (!simplified.is_ok())
      return Status(simplified.status().kind(),
                    "the stitched blocks: " + simplified.status().message());
    merged.mesh = std::move(simplified.value().mesh);
    merged.stats = simplified.value().stats;
    return merged;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while merging the blocks");
  }
}

}  // namespace lodbake
