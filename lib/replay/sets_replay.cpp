// Mode sets of the replay runtime: the LoD-recovery tests of Belmonte,
// Aguado and Sancho (ICCS 2006, section 4), which take their definition
// from Ribelles et al. 1999. The recovery is lib/strips' (StripRecovery);
// this file picks the LoDs, times each recovery and checks the result.
//
// Choices where the paper is vague:
// - "n% of the total number of LoDs": n = floor(lod_count * percent / 100)
//   positions (at least 2, so that both ends are visited), evenly spaced in
//   t = 0 .. 1 and rounded to the nearest LoD; "linear" maps t to
//   t (lod_count - 1), "exponential" to lod_count^t - 1, which takes "close
//   LoDs next to the maximum resolution and distant LoDs next to the
//   minimum" and lands exactly on both ends. Positions that round to the
//   LoD already taken are dropped, so a test never recovers the same LoD
//   twice in a row (the exponential descent's first positions are closer
//   than one LoD apart, so it holds fewer LoDs than the linear one).
// - "start at the maximum LoD, descend towards the minimum LoD and then
//   return to maximum LoD": the descent is LoD 0 (the full mesh) to the
//   base mesh; the ascent repeats it backwards without visiting the base
//   twice, ending at LoD 0.
// - The measure: the paper's Table 3 times recovery plus rendering; here
//   only the recovery is timed, one steady_clock interval around each call
//   (the tool's report is wall time, as the other modes'; the benchmark
//   tests/bench/strips_bench.cpp takes the thread's CPU time instead). Both
//   recoveries run at every step: the paper's coherent one (only strips
//   whose validity interval does not hold both LoDs are walked) and a fresh
//   one of every strip, which also gives the walk rate in indices per
//   second.
// - Each test starts from a newly created coherent recovery, so the tests'
//   order does not change their figures.
#include "lib/replay/sets_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <utility>

#include "formats/mesh/canonical_triangles.h"
#include "formats/sections/strp.h"
#include "lib/check/mesh_check.h"
#include "lib/replay/replay_check.h"

namespace lodbake {

const char* spacing_name(LodSpacing spacing) {
  return spacing == LodSpacing::kExponential ? "exponential" : "linear";
}

std::vector<double> paper_recovery_percents() {
  return {1, 3, 6, 10, 15, 20};
}

std::vector<uint32_t> recovery_test_lods(uint32_t lod_count, double percent, LodSpacing spacing) {
  if (lod_count == 0) return {};
  const uint32_t n =
      std::max<uint32_t>(2, static_cast<uint32_t>(static_cast<double>(lod_count) * percent / 100));
  std::vector<uint32_t> down;
  for (uint32_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    const double lod = spacing == LodSpacing::kExponential
                           ? std::pow(static_cast<double>(lod_count), t) - 1
                           : t * (lod_count - 1);
    const uint32_t l = std::min<uint32_t>(lod_count - 1, static_cast<uint32_t>(std::lround(lod)));
    if (down.empty() || l != down.back()) down.push_back(l);
  }
  std::vector<uint32_t> lods = down;
  for (size_t i = down.size() - 1; i-- > 0;)
    lods.push_back(down[i]);
  return lods;
}

SetsTestSummary summarize_sets_test(LodSpacing spacing, double percent,
                                    const std::vector<SetsStep>& steps) {
  SetsTestSummary summary;
  summary.spacing = spacing;
  summary.percent = percent;
  summary.lods = steps.size();
  double fresh_us = 0, coherent_us = 0;
  for (const SetsStep& step : steps) {
    summary.indices += step.indices;
    fresh_us += step.fresh_us;
    coherent_us += step.coherent_us;
  }
  if (steps.empty()) return summary;
  const double n = static_cast<double>(steps.size());
  const double indices = static_cast<double>(summary.indices);
  summary.fresh_us_per_lod = fresh_us / n;
  summary.coherent_us_per_lod = coherent_us / n;
  // indices / (us * 1e-6) / 1e6 = indices / us.
  summary.fresh_mindices_per_s = fresh_us > 0 ? indices / fresh_us : 0;
  summary.coherent_mindices_per_s = coherent_us > 0 ? indices / coherent_us : 0;
  return summary;
}

std::vector<std::array<uint32_t, 3>> recovered_corner_wedges(const std::vector<Triangle>& triangles,
                                                             const std::vector<Triangle>& level,
                                                             const CornerWedges& lookup) {
  // The level's triangles in canonical form with their face slots, sorted:
  // a recovered triangle finds its slot by binary search.
  std::vector<std::pair<Triangle, uint32_t>> slots(level.size());
  for (size_t f = 0; f < level.size(); ++f)
    slots[f] = {canonical_triangle(level[f]), static_cast<uint32_t>(f)};
  std::sort(slots.begin(), slots.end());
  std::vector<std::array<uint32_t, 3>> corners(triangles.size(), {kNoVertex, kNoVertex, kNoVertex});
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle key = canonical_triangle(triangles[t]);
    auto it = std::lower_bound(slots.begin(), slots.end(), std::make_pair(key, uint32_t{0}));
    if (it == slots.end() || it->first != key) continue;
    for (int k = 0; k < 3; ++k)
      corners[t][k] = lookup.wedge(it->second, triangles[t][k]);
  }
  return corners;
}

Result<SetsReplay> SetsReplay::create(const ProgressiveMesh& pm, const SetsGraph& graph,
                                      const CornerWedges* lookup, const PmWedges* wedges) {
  if ((lookup == nullptr) != (wedges == nullptr))
    return runtime_error("SETS replay: the corner lookup and the wedges go together");
  if (graph.vertex_count != pm.full_vertex_count() || graph.lod_count != pm.splits.size() + 1) {
    return invalid_input("SETS graph over " + std::to_string(graph.vertex_count) +
                         " vertices and " + std::to_string(graph.lod_count) +
                         " LoDs, the progressive mesh has " +
                         std::to_string(pm.full_vertex_count()) + " vertices and " +
                         std::to_string(pm.splits.size() + 1) + " LoDs");
  }
  try {
    SetsReplay replay(pm, graph);
    replay.lookup_ = lookup;
    replay.wedges_ = wedges;
    LODBAKE_ASSIGN_OR_RETURN(StripRecovery fresh, StripRecovery::create(graph));
    replay.fresh_.emplace(std::move(fresh));
    LODBAKE_RETURN_IF_ERROR(replay.restart());
    LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
    replay.refiner_.emplace(std::move(refiner));
    if (lookup != nullptr) LODBAKE_RETURN_IF_ERROR(replay.check_own_pm());
    return replay;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the SETS recovery");
  }
}

Status SetsReplay::restart() {
  try {
    LODBAKE_ASSIGN_OR_RETURN(StripRecovery coherent, StripRecovery::create(*graph_));
    coherent_.emplace(std::move(coherent));
    lod_.reset();
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the SETS recovery");
  }
}

Result<SetsStep> SetsReplay::step(uint32_t lod) {
  using Clock = std::chrono::steady_clock;
  lod_.reset();
  SetsStep step;
  step.lod = lod;
  auto start = Clock::now();
  LODBAKE_RETURN_IF_ERROR(coherent_->recover_coherent(lod));
  auto stop = Clock::now();
  step.coherent_us = std::chrono::duration<double, std::micro>(stop - start).count();
  step.coherent_walked_strips = coherent_->walked_strips();
  start = Clock::now();
  LODBAKE_RETURN_IF_ERROR(fresh_->recover(lod));
  stop = Clock::now();
  step.fresh_us = std::chrono::duration<double, std::micro>(stop - start).count();
  // Counted after the timing: the window rule of TriangleStrips.
  const std::vector<uint32_t>& indices = fresh_->indices();
  for (size_t s = 0; s < fresh_->strip_count(); ++s) {
    const uint32_t count = fresh_->count(s);
    if (count == 0) continue;
    ++step.strips;
    const uint32_t* v = indices.data() + fresh_->first(s);
    for (uint32_t i = 0; i + 2 < count; ++i)
      step.triangles += is_real_triangle(v[i], v[i + 1], v[i + 2]) ? 1 : 0;
  }
  step.indices = fresh_->index_count();
  lod_ = lod;
  return step;
}

std::vector<std::string> SetsReplay::check(std::optional<uint32_t> against_lod) {
  if (!lod_) return {"no LoD recovered"};
  try {
    std::vector<std::string> problems;
    const std::string differing = compare_recoveries(*coherent_, *fresh_);
    if (!differing.empty())
      problems.push_back("coherent recovery differs from fresh: " + differing);
    const uint32_t lod = against_lod.value_or(*lod_);
    if (lod >= lod_count()) return {"LoD " + std::to_string(lod) + " out of range"};
    const Status refined = refine_pm(lod);
    if (!refined.is_ok()) {
      problems.push_back(refined.message());
      return problems;
    }
    const TriangleMesh& pm_mesh = refiner_->mesh();
    for (std::string& problem : check_recovered_triangles(*fresh_, pm_mesh.triangles))
      problems.push_back(std::move(problem));
    TriangleMesh strips_mesh;
    strips_mesh.positions.assign(pm_mesh.vertex_count(), Vec3f{0, 0, 0});
    strips_mesh.triangles = strip_triangles(fresh_->to_strips());
    for (std::string& problem : triangulation_problems(strips_mesh))
      problems.push_back(std::move(problem));
    if (lookup_ != nullptr) {
      const std::vector<std::array<uint32_t, 3>> corners =
          recovered_corner_wedges(strips_mesh.triangles, pm_mesh.triangles, *lookup_);
      for (std::string& problem : corner_wedge_problems(corners, *wedges_))
        problems.push_back(std::move(problem));
      checked_corners_ += 3 * corners.size();
    }
    return problems;
  } catch (const std::bad_alloc&) {
    return {"out of memory checking the recovered strips"};
  }
}

// The corners' wedges are the PM's face slots' (recovered_corner_wedges()),
// so they are only right over the graph's own PM: the full mesh and the
// base are the strips' triangles at LoD 0 and at the coarsest LoD. Counts
// alone (create()'s first check) let another PM of the same size through.
Status SetsReplay::check_own_pm() {
  for (const uint32_t lod : {0u, lod_count() - 1}) {
    LODBAKE_RETURN_IF_ERROR(fresh_->recover(lod));
    LODBAKE_RETURN_IF_ERROR(refine_pm(lod));
    const std::vector<std::string> differ =
        check_recovered_triangles(*fresh_, refiner_->mesh().triangles);
    if (!differ.empty())
      return invalid_input("the progressive mesh (VSPL) is not the SETS graph's own: at LoD " +
                           std::to_string(lod) + ", " + differ.front());
  }
  return Status::ok();
}

Status SetsReplay::refine_pm(uint32_t lod) {
  const Status refined = refiner_->refine_to(pm_->full_vertex_count() - lod);
  if (refined.is_ok()) return refined;
  return invalid_input("the progressive mesh does not replay to LoD " + std::to_string(lod) + ": " +
                       refined.message());
}

Result<SetsLevel> SetsReplay::level() {
  if (!lod_) return invalid_input("no LoD recovered");
  try {
    LODBAKE_RETURN_IF_ERROR(refine_pm(*lod_));
    SetsLevel out;
    out.lod = *lod_;
    out.vertex_count = refiner_->vertex_count();
    out.triangles = strip_triangles(fresh_->to_strips());
    if (lookup_ != nullptr)
      out.corners = recovered_corner_wedges(out.triangles, refiner_->mesh().triangles, *lookup_);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory building the recovered LoD");
  }
}

Result<std::vector<SetsStep>> run_sets_test(SetsReplay* replay, const std::vector<uint32_t>& lods,
                                            bool validate) {
  try {
    LODBAKE_RETURN_IF_ERROR(replay->restart());
    std::vector<SetsStep> steps;
    steps.reserve(lods.size());
    for (size_t k = 0; k < lods.size(); ++k) {
      const std::string where = "step " + std::to_string(k) + ", LoD " + std::to_string(lods[k]);
      Result<SetsStep> step = replay->step(lods[k]);
      if (!step.is_ok())
        return Status(step.status().kind(), where + ": " + step.status().message());
      steps.push_back(step.value());
      if (!validate) continue;
      const std::vector<std::string> problems = replay->check();
      if (!problems.empty()) {
        std::string message = where + ": " + problems[0];
        for (size_t i = 1; i < problems.size(); ++i)
          message += "; " + problems[i];
        return Status(ErrorKind::kValidation, message);
      }
    }
    return steps;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory recording the recovery steps");
  }
}

}  // namespace lodbake
