// LoD recovery of the SETS model (Belmonte, Aguado, Sancho 2006, Figure 3
// and section 3.4).
//
// Choices where the paper is vague:
// - The paper's per-node `shift` is kept with an epoch instead of being
//   reset after each walk: a node whose epoch is not the current one has
//   not been visited in this recovery, so its arc is searched (first label
//   >= LoD: linear over short lists, binary search over long ones) and its
//   cursor set to the run's start; later visits take the next successor
//   directly. A node's vertex, arc range and cursor share one record, so a
//   visit touches one cache line plus the arc and the successor.
// - Coherence: each strip's change LoDs (every label + 1 of its beginnings
//   and arcs) are computed at load time; the current sequence is valid
//   between two consecutive ones (the paper's validity interval), so a
//   strip must be walked again exactly when one of its change LoDs lies in
//   (low, high] of the previous and the new LoD. Rather than testing every
//   strip's interval (the paper), the candidates come from the sorted
//   (change LoD, strip) event list by binary search; when there are more
//   events in the range than strips, every strip is walked instead.
// - A strip whose last beginning is END is empty from that beginning's LoD
//   on; a fresh recovery skips its walk there (at coarse LoDs most strips
//   are empty, and the per-strip search would dominate).
// - Hostile graphs: the walk checks each cursor against its run's end and
//   the output against the strip's slot (its LoD-0 length), so a malformed
//   graph gives a Status, never an out-of-bounds access or an endless walk.
#include "lib/strips/sets_recovery.h"

#include <algorithm>
#include <new>
#include <string>
#include <utility>

namespace lodbake {

Result<StripRecovery> StripRecovery::create(const SetsGraph& graph) {
  LODBAKE_RETURN_IF_ERROR(check_sets_structure(graph));
  try {
    StripRecovery r(graph);
    const size_t strips = graph.strip_count();
    r.nodes_.resize(graph.node_count());
    for (size_t n = 0; n < graph.node_count(); ++n)
      r.nodes_[n] = Node{graph.node_vertex[n], graph.arc_first[n], graph.arc_first[n + 1], 0, 0, 0};
    r.arcs_.resize(graph.arc_count() + 1);
    for (size_t a = 0; a < graph.arc_count(); ++a)
      r.arcs_[a] = Arc{graph.arc_lod[a], graph.successor_first[a]};
    r.arcs_.back() = Arc{graph.lod_count, graph.successor_first.back()};
    r.first_.assign(strips, 0);
    r.count_.assign(strips, 0);
    r.capacity_.assign(strips, 0);
    r.empty_from_.assign(strips, graph.lod_count);
    r.strip_epoch_.assign(strips, 0);
    uint64_t slots = 0;
    std::vector<std::pair<uint32_t, uint32_t>> events;
    for (size_t s = 0; s < strips; ++s) {
      // The walk at LoD 0 bounds every later one (validate_sets() checks it;
      // the fast walk refuses a longer sequence).
      LODBAKE_ASSIGN_OR_RETURN(std::vector<uint32_t> full, walk_strip(graph, s, 0));
      if (slots + full.size() > UINT32_MAX) return invalid_input("more than 2^32 - 1 indices");
      r.first_[s] = static_cast<uint32_t>(slots);
      r.capacity_[s] = static_cast<uint32_t>(full.size());
      slots += full.size();
      const uint32_t last = graph.beginning_first[s + 1] - 1;
      if (graph.beginning_node[last] == kSetsEnd)
        r.empty_from_[s] = last == graph.beginning_first[s] ? 0 : graph.beginning_lod[last - 1] + 1;
      std::vector<uint32_t> changes = strip_change_lods(graph, s);
      for (size_t k = 1; k < changes.size(); ++k)
        events.push_back({changes[k], static_cast<uint32_t>(s)});
    }
    std::sort(events.begin(), events.end());
    r.event_lod_.reserve(events.size());
    r.event_strip_.reserve(events.size());
    for (const auto& [lod, strip] : events) {
      r.event_lod_.push_back(lod);
      r.event_strip_.push_back(strip);
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

void StripRecovery::next_epoch() {
  if (++epoch_ == 0) {  // wrapped: forget every visit
    for (Node& node : nodes_)
      node.epoch = 0;
    std::fill(strip_epoch_.begin(), strip_epoch_.end(), 0);
    epoch_ = 1;
  }
}

Status StripRecovery::walk(size_t strip, uint32_t lod) {
  const SetsGraph& g = *graph_;
  const uint32_t* labels = g.beginning_lod.data();
  const uint32_t b =
      static_cast<uint32_t>(std::lower_bound(labels + g.beginning_first[strip],
                                             labels + g.beginning_first[strip + 1], lod) -
                            labels);
  uint32_t id = g.beginning_node[b];
  uint32_t* out = indices_.data() + first_[strip];
  uint32_t* const out_begin = out;
  uint32_t* const out_end = out + capacity_[strip];
  const uint32_t epoch = epoch_;
  Node* nodes = nodes_.data();
  const Arc* arcs = arcs_.data();
  const uint32_t* successors = g.successors.data();
  while (id != kSetsEnd) {
    if (out == out_end) return bad_walk(strip, lod, "longer than at LoD 0");
    Node& node = nodes[id];
    *out++ = node.vertex;
    if (node.epoch != epoch) {
      uint32_t a = node.arc_begin;
      if (node.arc_end - a <= 8) {
        while (arcs[a].lod < lod)
          ++a;  // the last label is the last LoD
      } else {
        a = static_cast<uint32_t>(
            std::lower_bound(arcs + a, arcs + node.arc_end, lod,
                             [](const Arc& arc, uint32_t l) { return arc.lod < l; }) -
            arcs);
      }
      node.epoch = epoch;
      node.cursor = arcs[a].succ_first;
      node.end = arcs[a + 1].succ_first;
    }
    if (node.cursor == node.end)
      return bad_walk(strip, lod, "a node is visited more often than its successor run allows");
    id = successors[node.cursor++];
  }
  const uint32_t written = static_cast<uint32_t>(out - out_begin);
  total_ = total_ - count_[strip] + written;
  count_[strip] = written;
  ++walked_strips_;
  walked_indices_ += written;
  return Status::ok();
}

Status StripRecovery::recover(uint32_t lod) {
  if (lod >= graph_->lod_count)
    return invalid_input("LoD " + std::to_string(lod) + " out of range (" +
                         std::to_string(graph_->lod_count) + " LoDs)");
  has_state_ = false;
  next_epoch();
  walked_strips_ = walked_indices_ = 0;
  for (size_t s = 0; s < count_.size(); ++s) {
    if (lod >= empty_from_[s]) {
      total_ -= count_[s];
      count_[s] = 0;
      continue;
    }
    LODBAKE_RETURN_IF_ERROR(walk(s, lod));
  }
  has_state_ = true;
  current_lod_ = lod;
  return Status::ok();
}

Status StripRecovery::recover_coherent(uint32_t lod) {
  if (!has_state_) return recover(lod);
  if (lod >= graph_->lod_count)
    return invalid_input("LoD " + std::to_string(lod) + " out of range (" +
                         std::to_string(graph_->lod_count) + " LoDs)");
  const uint32_t low = std::min(lod, current_lod_), high = std::max(lod, current_lod_);
  const size_t from =
      std::upper_bound(event_lod_.begin(), event_lod_.end(), low) - event_lod_.begin();
  const size_t to =
      std::upper_bound(event_lod_.begin(), event_lod_.end(), high) - event_lod_.begin();
  if (to - from > count_.size()) return recover(lod);
  has_state_ = false;  // until every changed strip is walked
  next_epoch();
  walked_strips_ = walked_indices_ = 0;
  for (size_t e = from; e < to; ++e) {
    const uint32_t s = event_strip_[e];
    if (strip_epoch_[s] == epoch_) continue;
    strip_epoch_[s] = epoch_;
    LODBAKE_RETURN_IF_ERROR(walk(s, lod));
  }
  has_state_ = true;
  current_lod_ = lod;
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
