// Mode dag of the replay runtime: MANAGE-TRAVERSAL (Zheng & Chan 2006,
// sections 4-5) with the priority-oriented traversal in budget mode.
// Choices where the paper leaves room:
// - priority of a split = its collapse error (VSPL) projected at the new
//   vertex's distance, in pixels; 0 when that vertex is outside the frustum
//   (the DAG carries no bounding spheres or normal cones, so there is no
//   back-face test here);
// - per frame, Fs is a max-heap and Fc a min-heap of priorities, rebuilt from
//   the fronts (entries that left a front are skipped when popped); a node of
//   Fc under the tolerance is collapsed, the top of Fs over it is split while
//   the budget allows, and when it does not, the top of Fc is collapsed if
//   its priority is lower (a swap), unless it is a parent of the node to
//   split; at most N changes per frame.
#include "lib/replay/dag_replay.h"

#include <chrono>
#include <cmath>
#include <new>
#include <queue>
#include <utility>

#include "lib/replay/mesh_validity.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

Result<DagReplay> DagReplay::create(const ProgressiveMesh& pm, const VsplitDag& dag) {
  if (dag.node_count() != pm.splits.size() || dag.base_vertex_count != pm.base.vertex_count()) {
    return invalid_input("DAG has " + std::to_string(dag.node_count()) + " nodes over " +
                         std::to_string(dag.base_vertex_count) +
                         " base vertices, the progressive mesh " +
                         std::to_string(pm.splits.size()) + " splits over " +
                         std::to_string(pm.base.vertex_count()));
  }
  try {
    LODBAKE_ASSIGN_OR_RETURN(DagFronts fronts, DagFronts::create(dag));
    DagReplay replay(pm, dag, std::move(fronts));
    LODBAKE_ASSIGN_OR_RETURN(replay.lineage_, build_split_lineage(pm));
    const SplitLineage& l = replay.lineage_;
    std::vector<uint32_t> changed(l.split_count(), 0);
    for (uint32_t s : l.changed_by) {
      if (s != kNoVertex && s < changed.size()) ++changed[s];
    }
    replay.added_.resize(l.split_count());
    for (size_t i = 0; i < l.split_count(); ++i) {
      const uint32_t created = l.created_offsets[i + 1] - l.created_offsets[i];
      if (created < changed[i]) {
        return runtime_error("split " + std::to_string(i) + " changes " +
                             std::to_string(changed[i]) + " triangles but creates only " +
                             std::to_string(created));
      }
      replay.added_[i] = created - changed[i];
    }
    replay.triangles_ = pm.base.triangle_count();
    return replay;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the DAG replay");
  }
}

bool DagReplay::is_parent(uint32_t parent, uint32_t node) const {
  for (uint32_t k = dag_->parent_offsets[node]; k < dag_->parent_offsets[node + 1]; ++k) {
    if (dag_->parents[k] == parent) return true;
  }
  return false;
}

float DagReplay::priority(uint32_t node) const {
  const VertexSplit& s = pm_->splits[node];
  const Vec3f& p = s.vt_position;
  for (const std::array<float, 4>& q : view_.frustum) {
    if (q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] < 0) return 0;
  }
  double d2 = 0;
  for (int i = 0; i < 3; ++i)
    d2 += (double{p[i]} - view_.eye[i]) * (double{p[i]} - view_.eye[i]);
  const double d = std::max(std::sqrt(d2), 1e-12);
  return static_cast<float>(double{s.error} / d * pixels_per_unit_at_1_);
}

Result<DagFrameStats> DagReplay::adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                                       const DagReplayOptions& options) {
  try {
    const auto start = std::chrono::steady_clock::now();
    view_ = view_parameters(frame, options.viewport, options.viewport.near_fraction * sphere.radius,
                            options.tolerance_pixels);
    pixels_per_unit_at_1_ =
        options.viewport.height / (2 * std::tan(double{frame.fov_degrees} * kPi / 360));
    using Entry = std::pair<float, uint32_t>;
    std::priority_queue<Entry> fs;                                           // max first
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> fc;  // min first
    for (uint32_t n : fronts_.split_front())
      fs.push({priority(n), n});
    for (uint32_t n : fronts_.collapse_front())
      fc.push({priority(n), n});
    const float tol = options.tolerance_pixels;
    DagFrameStats stats;
    auto after_split = [&](uint32_t n) {
      fc.push({priority(n), n});
      for (const uint32_t* c = fronts_.children_begin(n); c != fronts_.children_end(n); ++c) {
        if (fronts_.can_split(*c)) fs.push({priority(*c), *c});
      }
    };
    auto after_collapse = [&](uint32_t n) {
      fs.push({priority(n), n});
      for (uint32_t k = dag_->parent_offsets[n]; k < dag_->parent_offsets[n + 1]; ++k) {
        const uint32_t p = dag_->parents[k];
        if (fronts_.can_collapse(p)) fc.push({priority(p), p});
      }
    };
    while (stats.splits + stats.collapses < options.max_changes) {
      while (!fs.empty() && !fronts_.can_split(fs.top().second))
        fs.pop();
      while (!fc.empty() && !fronts_.can_collapse(fc.top().second))
        fc.pop();
      if (!fc.empty() && fc.top().first < tol) {
        const uint32_t c = fc.top().second;
        fc.pop();
        LODBAKE_RETURN_IF_ERROR(fronts_.collapse(c));
        triangles_ -= added_[c];
        ++stats.collapses;
        after_collapse(c);
        continue;
      }
      if (fs.empty() || fs.top().first < tol) break;
      const uint32_t s = fs.top().second;
      if (triangles_ + added_[s] <= options.triangle_budget) {
        fs.pop();
        LODBAKE_RETURN_IF_ERROR(fronts_.split(s));
        triangles_ += added_[s];
        ++stats.splits;
        after_split(s);
        continue;
      }
      if (fc.empty() || !(fc.top().first < fs.top().first) || is_parent(fc.top().second, s)) break;
      const uint32_t c = fc.top().second;
      fc.pop();
      LODBAKE_RETURN_IF_ERROR(fronts_.collapse(c));
      triangles_ -= added_[c];
      ++stats.collapses;
      after_collapse(c);
    }
    stats.split_front = fronts_.split_front().size();
    stats.collapse_front = fronts_.collapse_front().size();
    stats.triangles = triangles_;
    stats.traversal_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory traversing the DAG");
  }
}

std::vector<std::string> DagReplay::check() const {
  std::vector<std::string> problems = fronts_.check_counters();
  TriangleMesh mesh;
  mesh.positions.assign(pm_->base.vertex_count() + pm_->splits.size(), Vec3f{0, 0, 0});
  mesh.triangles = dag_cut_triangles(lineage_, fronts_);
  for (std::string& problem : triangulation_problems(mesh))
    problems.push_back(std::move(problem));
  if (mesh.triangle_count() != triangles_) {
    problems.push_back("triangle count " + std::to_string(triangles_) + " but the cut has " +
                       std::to_string(mesh.triangle_count()) + " triangles");
  }
  return problems;
}

}  // namespace lodbake
