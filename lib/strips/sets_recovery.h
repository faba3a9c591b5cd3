// Recovering the triangle strips of any level of detail from a SETS graph:
// the paper's LoD recovery (Figure 3) and its coherence by validity
// intervals (section 3.4). The runtime part: no CGAL, no allocation per
// recovery.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/support/status.h"

namespace lodbake {

class StripRecovery {
 public:
  /// Prepares recovery from `graph` (which must outlive this object): checks
  /// check_sets_structure(), walks every strip at LoD 0 to size its slot in
  /// the index buffer, and sorts every strip's change LoDs
  /// (strip_change_lods()) into one event list. No strips are recovered yet.
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
  Status walk(size_t strip, uint32_t lod);
  Status bad_walk(size_t strip, uint32_t lod, const char* what) const;
  void next_epoch();

  // Everything a walk touches per node in one 24-byte record.
  struct Node {
    uint32_t vertex;
    uint32_t arc_begin, arc_end;  // into arcs_
    uint32_t epoch;               // == epoch_ when cursor/end are set for this recovery
    uint32_t cursor;              // next successor to take
    uint32_t end;                 // end of the successor run valid at the LoD
  };
  struct Arc {
    uint32_t lod;         // label: the last LoD this run is valid at
    uint32_t succ_first;  // run is successors[succ_first, next arc's succ_first)
  };
  const SetsGraph* graph_;
  std::vector<Node> nodes_;
  std::vector<Arc> arcs_;  // graph arcs plus one sentinel
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

}  // namespace lodbake
