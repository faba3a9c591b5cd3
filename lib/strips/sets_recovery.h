// Recovering the triangle strips of any level of detail from a SETS graph:
// the paper's LoD recovery (Figure 3) and its coherence by validity
// intervals (section 3.4). The runtime part: no CGAL, no allocation per
// recovery.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/support/status.h"

namespace lodbake {

class StripRecovery {
 public:
  /// Prepares recovery from `graph` (which must outlive this object): checks
  /// check_sets_structure(), walks every strip at LoD 0 to size its slot in
  /// the index buffer, lays out each strip's nodes in the order walks at
  /// seven sampled LoDs (coarsest first) visit them, and sorts every strip's
  /// change LoDs (strip_change_lods()) into one event list. No strips are
  /// recovered yet.
  /// \return kInvalidInput when the structure check or a LoD-0 walk fails;
  ///         kRuntime when memory runs out.
  static Result<StripRecovery> create(const SetsGraph& graph);

  /// Recovers every strip at `lod` (0 = full mesh .. lod_count()-1 = base).
  /// \return kInvalidInput when lod is out of range or a walk fails (a
  ///         graph that passed validate_sets() never fails); the strips are
  ///         then unspecified until the next successful call.
  Status recover(uint32_t lod);
  /// Same result as recover(lod), walking only the strips whose validity
  /// interval (between two consecutive change LoDs of the strip) does not
  /// hold both the previous LoD and `lod`: the strips with a change event
  /// between the two, found in the load-time sorted list of (change LoD,
  /// strip) events, so the cost follows what changed, not the strip count.
  /// Without a previous successful recovery it is recover().
  Status recover_coherent(uint32_t lod);

  uint32_t lod_count() const { return graph_->lod_count; }
  size_t strip_count() const { return count_.size(); }
  /// Strip s is indices()[first(s), first(s) + count(s)); slots are fixed,
  /// sized by LoD 0, so a coherent recovery rewrites changed strips in place
  /// (for glMultiDrawElements-style rendering, or to_strips() to pack).
  const std::vector<uint32_t>& indices() const { return indices_; }
  uint32_t first(size_t s) const { return first_[s]; }
  uint32_t count(size_t s) const { return count_[s]; }
  /// Indices of all recovered strips (sum of count()).
  uint64_t index_count() const { return total_; }
  /// Strips walked and indices written by the last recovery.
  uint64_t walked_strips() const { return walked_strips_; }
  uint64_t walked_indices() const { return walked_indices_; }
  /// The recovered strips packed (empty strips dropped).
  TriangleStrips to_strips() const;

 private:
  explicit StripRecovery(const SetsGraph& graph) : graph_(&graph) {}
  // One strip walk in progress: the next node and the output cursor.
  struct Lane {
    uint32_t strip;
    uint32_t id;
    uint32_t out, out_end;  // into indices_
  };
  static constexpr size_t kLanes = 16;
  void start_lane(Lane* lane, uint32_t strip, uint32_t lod) const;
  void finish_lane(const Lane& lane);
  template <typename NextStrip>
  Status walk_strips(uint32_t lod, NextStrip next_strip);
  Status bad_walk(size_t strip, uint32_t lod, const char* what) const;
  void next_epoch();

  Status lay_out_records();

  // Each node is one record in pool_ (each strip's records in the order
  // walks from its coarsest LoD to LoD 0 visit them), so that a first visit reads
  // one or two cache lines: the words below, then the arc labels, the
  // arcs' successor run starts (pool offsets, one more than the arcs) and
  // the successors themselves (pool offsets of their records, or kSetsEnd).
  static constexpr uint32_t kVertex = 0;
  static constexpr uint32_t kEpoch = 1;   // == epoch_ when cursor/end are set for this recovery
  static constexpr uint32_t kCursor = 2;  // next successor to take
  static constexpr uint32_t kEnd = 3;     // end of the successor run valid at the LoD
  static constexpr uint32_t kArcCount = 4;
  static constexpr uint32_t kLabels = 5;
  const SetsGraph* graph_;
  std::vector<uint32_t> pool_;
  std::vector<uint32_t> beginning_record_;  // graph.beginning_node as pool offsets
  uint32_t epoch_ = 0;
  std::vector<uint32_t> strip_epoch_;
  std::vector<uint32_t> event_lod_, event_strip_;  // sorted by (LoD, strip)
  bool has_state_ = false;                         // every strip holds current_lod_
  uint32_t current_lod_ = 0;
  std::vector<uint32_t> indices_;
  std::vector<uint32_t> first_, count_, capacity_;
  std::vector<uint32_t> empty_from_;  // strip s has no index at LoDs >= empty_from_[s]
  uint64_t total_ = 0;
  uint64_t walked_strips_ = 0;
  uint64_t walked_indices_ = 0;
};

/// The checks of a recovered LoD (lodbake-replay --mode sets --validate and
/// the strips tests): the non-degenerate triangles `recovery`'s strips
/// describe must be the non-degenerate `lod_triangles` (the progressive
/// mesh's triangles at the LoD recovered) with their orientation, each once
/// (compare_strip_triangles() with "PM"). One line per kind of difference;
/// empty when they agree.
std::vector<std::string> check_recovered_triangles(const StripRecovery& recovery,
                                                   const std::vector<Triangle>& lod_triangles);

/// Where two recoveries of the same graph (a coherent and a fresh one at
/// the same LoD) hold different strips: empty when every strip has the same
/// indices, else one line with the number of differing strips and the
/// first one.
std::string compare_recoveries(const StripRecovery& a, const StripRecovery& b);

}  // namespace lodbake
