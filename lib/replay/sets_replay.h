// Replaying the SETS strip graph (issue 8, mode sets): the LoD-recovery
// tests of Belmonte, Aguado and Sancho (ICCS 2006, section 4 and Table 3,
// after Ribelles et al. 1999): recover 1, 3, 6, 10, 15 and 20% of all LoDs,
// spaced linearly or exponentially, from the finest LoD to the coarsest and
// back, and measure the recovery alone. Not camera-driven: a step is one
// LoD recovered. The LoD sequences are shared with tests/bench/strips_bench.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/sections/sets.h"
#include "formats/support/status.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/wedge_replay.h"
#include "lib/strips/sets_recovery.h"

namespace lodbake {

enum class LodSpacing { kLinear, kExponential };

/// "linear" or "exponential".
const char* spacing_name(LodSpacing spacing);

/// The paper's percentages of all LoDs: 1, 3, 6, 10, 15, 20.
std::vector<double> paper_recovery_percents();

/// The LoDs one recovery test visits, LoD 0 (the full mesh) first.
/// n = max(2, floor(lod_count * percent / 100)) positions t_i = i / (n - 1),
/// i = 0 .. n-1, become LoDs rounded to the nearest integer (std::lround):
/// linear, t (lod_count - 1); exponential, lod_count^t - 1 (dense near the
/// full mesh, sparse near the base: the model moving away). Both put t = 0
/// on LoD 0 and t = 1 on the coarsest LoD, lod_count - 1. A position that
/// rounds to the LoD before it is dropped, so the descent is strictly
/// increasing (and may hold fewer than n LoDs: the exponential spacing's
/// first steps are closer than one LoD). The ascent is the descent
/// reversed without repeating the coarsest LoD, so the sequence ends at
/// LoD 0 again and holds 2 d - 1 LoDs for a descent of d.
/// \pre lod_count >= 1, 0 < percent <= 100 (a lod_count of 1 gives {0}).
std::vector<uint32_t> recovery_test_lods(uint32_t lod_count, double percent, LodSpacing spacing);

/// One recovery step (one LoD).
struct SetsStep {
  uint32_t lod = 0;
  uint64_t strips = 0;                  ///< non-empty strips at the LoD
  uint64_t indices = 0;                 ///< strip indices at the LoD
  uint64_t triangles = 0;               ///< non-degenerate triangles the strips describe
  uint64_t coherent_walked_strips = 0;  ///< strips the coherent recovery walked
  double fresh_us = 0;                  ///< StripRecovery::recover(lod), steady_clock
  double coherent_us = 0;               ///< StripRecovery::recover_coherent(lod), steady_clock
};

/// The totals of one test (one spacing and percent).
struct SetsTestSummary {
  LodSpacing spacing = LodSpacing::kLinear;
  double percent = 0;
  size_t lods = 0;  ///< LoDs recovered (steps)
  uint64_t indices = 0;
  double fresh_us_per_lod = 0;
  double coherent_us_per_lod = 0;
  /// Strip indices recovered per second of recovery time, in millions: the
  /// fresh walk's rate (every index is walked) and the coherent output rate
  /// (the recovered LoDs' indices per second, what coherence buys).
  double fresh_mindices_per_s = 0;
  double coherent_mindices_per_s = 0;
};

/// Means and rates over `steps` (zero for an empty list or a zero time).
SetsTestSummary summarize_sets_test(LodSpacing spacing, double percent,
                                    const std::vector<SetsStep>& steps);

/// The wedge of every corner of a recovered LoD's triangles: `triangles`
/// (the strips' non-degenerate triangles, in PM vertex ids) against
/// `level`, the progressive mesh's triangles at the same LoD as PmRefiner
/// lays them out (triangle i is face slot i: the base triangles, then each
/// split's added faces). A recovered triangle is the level's triangle with
/// the same corners in the same cyclic order (what
/// check_recovered_triangles() asks, each once), so it is that face slot,
/// and its corner at vertex v takes lookup.wedge(slot, v): the wedge that
/// level of the PM gives it. A triangle the level does not hold gets
/// kNoVertex at every corner (corner_wedge_problems() counts them).
std::vector<std::array<uint32_t, 3>> recovered_corner_wedges(const std::vector<Triangle>& triangles,
                                                             const std::vector<Triangle>& level,
                                                             const CornerWedges& lookup);

/// One recovered LoD as a mesh: the strips' non-degenerate triangles (strip
/// by strip, in PM vertex ids; vertices 0 .. vertex_count - 1 are the PM's
/// at the LoD) and, over an asset's strips, each corner's wedge.
struct SetsLevel {
  uint32_t lod = 0;
  size_t vertex_count = 0;
  std::vector<Triangle> triangles;
  std::vector<std::array<uint32_t, 3>> corners;  ///< per triangle; empty without wedges
};

/// A SETS graph, its progressive mesh, a fresh and a coherent recovery of
/// it, and (for check()) the PM replayed to the last recovered LoD.
class SetsReplay {
 public:
  /// Fails when the graph is not over the PM (vertex_count !=
  /// full_vertex_count(), lod_count != splits + 1), the graph fails
  /// StripRecovery::create() or the PM's base mesh is malformed. `pm` and
  /// `graph` must outlive the replay. An asset's strips (WEDG beside the
  /// VSPL) give `wedges` and `lookup` (CornerWedges::create(pm, *wedges)),
  /// both or neither: every level() then has its corners' wedges and
  /// check() checks them. They must outlive the replay too. With them, a
  /// PM that is not the graph's own (the strips' triangles at LoD 0 or at
  /// the coarsest LoD are not the PM's) is refused (kInvalidInput).
  static Result<SetsReplay> create(const ProgressiveMesh& pm, const SetsGraph& graph,
                                   const CornerWedges* lookup = nullptr,
                                   const PmWedges* wedges = nullptr);

  uint32_t lod_count() const { return graph_->lod_count; }

  /// Starts a new test: the coherent recovery forgets its state, so a
  /// test's first coherent recovery walks every strip as it would after
  /// loading, whatever test ran before.
  Status restart();

  /// Recovers `lod` with recover_coherent() then recover() (each timed
  /// alone) and counts the fresh recovery's strips, indices and triangles.
  /// \return kInvalidInput when lod is out of range or a walk fails.
  Result<SetsStep> step(uint32_t lod);

  /// Problems of the last step's strips, empty when all is well: the
  /// coherent recovery equals the fresh one (compare_recoveries()); the
  /// fresh strips' non-degenerate triangles are the PM's triangles at the
  /// LoD with their orientation (check_recovered_triangles(), the PM
  /// replayed by PmRefiner); and they form a valid triangulation
  /// (triangulation_problems(): no repeated or out-of-range index of the
  /// LoD's vertices, no duplicate, no edge with more than two faces or
  /// walked twice the same way). With wedges, every corner has one and a
  /// face's three belong to one primitive (corner_wedge_problems() of
  /// recovered_corner_wedges()). `against_lod` compares with the PM at
  /// another LoD instead (for tests that show a mismatch is found).
  std::vector<std::string> check(std::optional<uint32_t> against_lod = std::nullopt);

  /// The last step's fresh recovery as a mesh, with its corners' wedges
  /// when the replay has them (the PM is replayed to the LoD).
  /// \return kInvalidInput without a successful step, or when the PM does
  ///         not replay to the LoD.
  Result<SetsLevel> level();

  bool has_wedges() const { return lookup_ != nullptr; }
  /// Corners whose wedges check() has checked since the replay was created.
  uint64_t checked_corners() const { return checked_corners_; }

  const StripRecovery& fresh() const { return *fresh_; }
  const StripRecovery& coherent() const { return *coherent_; }

 private:
  SetsReplay(const ProgressiveMesh& pm, const SetsGraph& graph) : pm_(&pm), graph_(&graph) {}
  Status refine_pm(uint32_t lod);
  Status check_own_pm();

  const ProgressiveMesh* pm_;
  const SetsGraph* graph_;
  const CornerWedges* lookup_ = nullptr;
  const PmWedges* wedges_ = nullptr;
  uint64_t checked_corners_ = 0;
  std::optional<StripRecovery> fresh_, coherent_;
  std::optional<PmRefiner> refiner_;
  std::optional<uint32_t> lod_;  // of the last successful step
};

/// One test: restart(), then step() on every LoD of `lods` in order; with
/// `validate`, check() after every step.
/// \return the steps; a failed step's Status prefixed "step K, LoD N: ";
///         a check's problems as kValidation "step K, LoD N: " + the
///         problems joined by "; ".
Result<std::vector<SetsStep>> run_sets_test(SetsReplay* replay, const std::vector<uint32_t>& lods,
                                            bool validate);

}  // namespace lodbake
