// LoD recovery of the SETS model (Belmonte, Aguado, Sancho 2006, Figure 3
// and section 3.4).
//
// Choices where the paper is vague:
// - The paper's per-node `shift` is kept with an epoch instead of being
//   reset after each walk: a node whose epoch is not the current one has
//   not been visited in this recovery, so its arc is found by binary search
//   (first label >= LoD) and its cursor set to the run's start; later
//   visits take the next successor directly.
// - Coherence: each strip's change LoDs (0 and every label + 1 of its
//   beginnings and arcs) are computed at load time; the current sequence is
//   valid on [change[k], change[k+1]) and a coherent recovery walks a strip
//   only when the LoD leaves that interval (binary search for the new one).
// - Hostile graphs: the walk checks each cursor against its run's end and
//   the output against the strip's slot (its LoD-0 length), so a malformed
//   graph gives a Status, never an out-of-bounds access or an endless walk.
#include "lib/strips/sets_recovery.h"

#include <algorithm>
#include <new>
#include <string>

namespace lodbake {

Result<StripRecovery> StripRecovery::create(const SetsGraph& graph) {
  LODBAKE_RETURN_IF_ERROR(check_sets_structure(graph));
  try {
    StripRecovery r(graph);
    const size_t strips = graph.strip_count();
    r.nodes_.assign(graph.node_count(), NodeState{0, 0, 0});
    r.first_.assign(strips, 0);
    r.count_.assign(strips, 0);
    r.capacity_.assign(strips, 0);
    r.valid_lo_.assign(strips, 1);  // empty intervals: nothing recovered yet
    r.valid_hi_.assign(strips, 0);
    r.change_first_.push_back(0);
    uint64_t slots = 0;
    for (size_t s = 0; s < strips; ++s) {
      // The walk at LoD 0 bounds every later one (validate_sets() checks it;
      // the fast walk refuses a longer sequence).
      LODBAKE_ASSIGN_OR_RETURN(std::vector<uint32_t> full, walk_strip(graph, s, 0));
      if (slots + full.size() > UINT32_MAX) return invalid_input("more than 2^32 - 1 indices");
      r.first_[s] = static_cast<uint32_t>(slots);
      r.capacity_[s] = static_cast<uint32_t>(full.size());
      slots += full.size();
      std::vector<uint32_t> changes = strip_change_lods(graph, s);
      r.change_lods_.insert(r.change_lods_.end(), changes.begin(), changes.end());
      r.change_first_.push_back(static_cast<uint32_t>(r.change_lods_.size()));
    }
    r.indices_.assign(slots, 0);
    return r;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing strip recovery");
  }
}

Status StripRecovery::bad_walk(size_t strip, uint32_t lod, const char* what) const {
  return invalid_input("strip " + std::to_string(strip) + " at LoD " + std::to_string(lod) + ": " +
                       what);
}

Status StripRecovery::walk(size_t strip, uint32_t lod) {
  const SetsGraph& g = *graph_;
  const uint32_t* labels = g.beginning_lod.data();
  const uint32_t b =
      static_cast<uint32_t>(std::lower_bound(labels + g.beginning_first[strip],
                                             labels + g.beginning_first[strip + 1], lod) -
                            labels);
  uint32_t node = g.beginning_node[b];
  uint32_t* out = indices_.data() + first_[strip];
  uint32_t* const out_begin = out;
  uint32_t* const out_end = out + capacity_[strip];
  const uint32_t epoch = epoch_;
  NodeState* states = nodes_.data();
  const uint32_t* vertex = g.node_vertex.data();
  const uint32_t* successors = g.successors.data();
  while (node != kSetsEnd) {
    if (out == out_end) return bad_walk(strip, lod, "longer than at LoD 0");
    *out++ = vertex[node];
    NodeState& state = states[node];
    if (state.epoch != epoch) {
      const uint32_t* arc_labels = g.arc_lod.data();
      const uint32_t arc =
          static_cast<uint32_t>(std::lower_bound(arc_labels + g.arc_first[node],
                                                 arc_labels + g.arc_first[node + 1], lod) -
                                arc_labels);
      state.epoch = epoch;
      state.cursor = g.successor_first[arc];
      state.end = g.successor_first[arc + 1];
    }
    if (state.cursor == state.end)
      return bad_walk(strip, lod, "a node is visited more often than its successor run allows");
    node = successors[state.cursor++];
  }
  const uint32_t written = static_cast<uint32_t>(out - out_begin);
  total_ = total_ - count_[strip] + written;
  count_[strip] = written;
  ++walked_strips_;
  walked_indices_ += written;
  return Status::ok();
}

void StripRecovery::set_interval(size_t strip, uint32_t lod) {
  const uint32_t* begin = change_lods_.data() + change_first_[strip];
  const uint32_t* end = change_lods_.data() + change_first_[strip + 1];
  const uint32_t* next = std::upper_bound(begin, end, lod);  // begin holds 0 <= lod
  valid_lo_[strip] = next[-1];
  valid_hi_[strip] = next == end ? graph_->lod_count : *next;
}

Status StripRecovery::recover(uint32_t lod) {
  if (lod >= graph_->lod_count)
    return invalid_input("LoD " + std::to_string(lod) + " out of range (" +
                         std::to_string(graph_->lod_count) + " LoDs)");
  if (++epoch_ == 0) {  // wrapped: forget every visit
    for (NodeState& state : nodes_)
      state.epoch = 0;
    epoch_ = 1;
  }
  walked_strips_ = walked_indices_ = 0;
  for (size_t s = 0; s < count_.size(); ++s) {
    Status status = walk(s, lod);
    if (!status.is_ok()) {
      valid_lo_[s] = 1;
      valid_hi_[s] = 0;
      return status;
    }
    set_interval(s, lod);
  }
  return Status::ok();
}

Status StripRecovery::recover_coherent(uint32_t lod) {
  if (lod >= graph_->lod_count)
    return invalid_input("LoD " + std::to_string(lod) + " out of range (" +
                         std::to_string(graph_->lod_count) + " LoDs)");
  if (++epoch_ == 0) {
    for (NodeState& state : nodes_)
      state.epoch = 0;
    epoch_ = 1;
  }
  walked_strips_ = walked_indices_ = 0;
  for (size_t s = 0; s < count_.size(); ++s) {
    if (lod >= valid_lo_[s] && lod < valid_hi_[s]) continue;
    Status status = walk(s, lod);
    if (!status.is_ok()) {
      valid_lo_[s] = 1;
      valid_hi_[s] = 0;
      return status;
    }
    set_interval(s, lod);
  }
  return Status::ok();
}

TriangleStrips StripRecovery::to_strips() const {
  TriangleStrips strips;
  strips.vertex_count = graph_->vertex_count;
  strips.indices.reserve(total_);
  for (size_t s = 0; s < count_.size(); ++s) {
    if (count_[s] == 0) continue;
    strips.indices.insert(strips.indices.end(), indices_.begin() + first_[s],
                          indices_.begin() + first_[s] + count_[s]);
    strips.first.push_back(static_cast<uint32_t>(strips.indices.size()));
  }
  return strips;
}

}  // namespace lodbake
