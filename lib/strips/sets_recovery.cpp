// LoD recovery of the SETS model (Belmonte, Aguado, Sancho 2006, Figure 3
// and section 3.4).
//
// Choices where the paper is vague:
// - The paper's per-node `shift` is kept with an epoch instead of being
//   reset after each walk: a node whose epoch is not the current one has
//   not been visited in this recovery, so its arc is searched (first label
//   >= LoD: linear over short lists, binary search over long ones) and its
//   cursor set to the run's start; later visits take the next successor
//   directly.
// - Memory layout: each node is one variable-length record in one pool of
//   32-bit words (vertex, epoch, cursor, run end, arc count, then its arc
//   labels, its successor run starts and its successors), and successors
//   name records by pool offset: a first visit reads one or two adjacent
//   cache lines instead of a node record, an arc and a successor in three
//   arrays. A strip's records are laid out in the order the walks at
//   sampled LoDs visit them, coarsest LoD first: at a coarse LoD the live
//   nodes sit together at the front of the strip's range, and at fine
//   LoDs each sample's newcomers follow in walk order. (Ordering by vertex
//   id instead halved the fine-LoD rate; plain creation order, the LoD-0
//   walk order, was 5-25% slower than this on the dragon.)
// - Walks are pointer chases (the next node is known only after reading
//   the successor), so at middle and coarse LoDs, where nearly every visit
//   misses the cache, one walk waits on one miss at a time. Up to kLanes
//   strips are walked interleaved, one node visit each in turn, with the
//   next record prefetched: the misses of different strips overlap. A
//   node belongs to one strip, so the interleaving cannot change a result.
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
    LODBAKE_RETURN_IF_ERROR(r.lay_out_records());
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

Status StripRecovery::lay_out_records() {
  const SetsGraph& g = *graph_;
  const size_t nodes = g.node_count();
  // Each strip's nodes in the order walks visit them from the coarsest
  // sampled LoD to the finest: a walk at any LoD then reads mostly the
  // strip's first records, those of the nodes still alive.
  std::vector<uint32_t> order;
  order.reserve(nodes);
  std::vector<uint8_t> placed(nodes, 0);
  std::vector<std::pair<uint32_t, uint32_t>> by_vertex;
  for (size_t s = 0; s < g.strip_count(); ++s) {
    by_vertex.clear();
    for (uint32_t n = g.node_first[s]; n < g.node_first[s + 1]; ++n)
      by_vertex.push_back({g.node_vertex[n], n});
    std::sort(by_vertex.begin(), by_vertex.end());
    for (double fraction : {1.0, 0.97, 0.9, 0.75, 0.5, 0.25, 0.0}) {
      const uint32_t lod = static_cast<uint32_t>(fraction * (g.lod_count - 1));
      // A walk that fails here (a malformed graph) only leaves its nodes to
      // a later sample; recover() reports the failure at that LoD.
      const Result<std::vector<uint32_t>> sequence = walk_strip(g, s, lod);
      if (!sequence.is_ok()) continue;
      for (uint32_t v : sequence.value()) {
        const auto it = std::lower_bound(by_vertex.begin(), by_vertex.end(),
                                         std::pair<uint32_t, uint32_t>{v, 0});
        if (it == by_vertex.end() || it->first != v || placed[it->second]) continue;
        placed[it->second] = 1;
        order.push_back(it->second);
      }
    }
    for (uint32_t n = g.node_first[s]; n < g.node_first[s + 1]; ++n)
      if (!placed[n]) order.push_back(n);
  }
  std::vector<uint32_t> offset(nodes);
  uint64_t words = 0;
  for (uint32_t n : order) {
    offset[n] = static_cast<uint32_t>(words);
    const uint64_t arcs = g.arc_first[n + 1] - g.arc_first[n];
    const uint64_t successors =
        g.successor_first[g.arc_first[n + 1]] - g.successor_first[g.arc_first[n]];
    words += kLabels + 2 * arcs + 1 + successors;
    if (words >= kSetsEnd) return invalid_input("graph too large for recovery (2^32 words)");
  }
  pool_.assign(words, 0);
  uint32_t* pool = pool_.data();
  for (size_t n = 0; n < nodes; ++n) {
    uint32_t* record = pool + offset[n];
    const uint32_t arc_begin = g.arc_first[n], arcs = g.arc_first[n + 1] - arc_begin;
    record[kVertex] = g.node_vertex[n];
    record[kArcCount] = arcs;
    uint32_t* labels = record + kLabels;
    uint32_t* runs = labels + arcs;
    uint32_t* successors = runs + arcs + 1;
    const uint32_t succ_begin = g.successor_first[arc_begin];
    const uint32_t base = static_cast<uint32_t>(successors - pool);
    for (uint32_t a = 0; a <= arcs; ++a) {
      if (a < arcs) labels[a] = g.arc_lod[arc_begin + a];
      runs[a] = base + (g.successor_first[arc_begin + a] - succ_begin);
    }
    for (uint32_t k = succ_begin; k < g.successor_first[arc_begin + arcs]; ++k)
      *successors++ = g.successors[k] == kSetsEnd ? kSetsEnd : offset[g.successors[k]];
  }
  beginning_record_.resize(g.beginning_node.size());
  for (size_t b = 0; b < g.beginning_node.size(); ++b)
    beginning_record_[b] = g.beginning_node[b] == kSetsEnd ? kSetsEnd : offset[g.beginning_node[b]];
  return Status::ok();
}

Status StripRecovery::bad_walk(size_t strip, uint32_t lod, const char* what) const {
  return invalid_input("strip " + std::to_string(strip) + " at LoD " + std::to_string(lod) + ": " +
                       what);
}

void StripRecovery::next_epoch() {
  if (++epoch_ == 0) {  // wrapped: forget every visit
    for (size_t o = 0; o < pool_.size();) {
      const uint32_t* record = pool_.data() + o;
      const uint32_t arcs = record[kArcCount];
      const uint32_t* runs = record + kLabels + arcs;
      pool_[o + kEpoch] = 0;
      o += kLabels + 2 * arcs + 1 + (runs[arcs] - runs[0]);
    }
    std::fill(strip_epoch_.begin(), strip_epoch_.end(), 0);
    epoch_ = 1;
  }
}

void StripRecovery::start_lane(Lane* lane, uint32_t strip, uint32_t lod) const {
  const SetsGraph& g = *graph_;
  const uint32_t* labels = g.beginning_lod.data();
  const uint32_t* b = labels + g.beginning_first[strip];
  const uint32_t* const b_end = labels + g.beginning_first[strip + 1];
  while (*b < lod && b + 1 < b_end)  // short lists; the last label is the last LoD
    ++b;
  lane->strip = strip;
  lane->id = beginning_record_[b - labels];
  lane->out = first_[strip];
  lane->out_end = first_[strip] + capacity_[strip];
  if (lane->id != kSetsEnd) __builtin_prefetch(pool_.data() + lane->id);
}

void StripRecovery::finish_lane(const Lane& lane) {
  const uint32_t written = lane.out - first_[lane.strip];
  total_ = total_ - count_[lane.strip] + written;
  count_[lane.strip] = written;
  ++walked_strips_;
  walked_indices_ += written;
}

template <typename NextStrip>
Status StripRecovery::walk_strips(uint32_t lod, NextStrip next_strip) {
  Lane lanes[kLanes];
  size_t active = 0;
  uint32_t s;
  while (active < kLanes && next_strip(&s))
    start_lane(&lanes[active++], s, lod);
  const uint32_t epoch = epoch_;
  uint32_t* pool = pool_.data();
  uint32_t* indices = indices_.data();
  while (active > 0) {
    for (size_t i = 0; i < active;) {
      Lane& lane = lanes[i];
      if (lane.id == kSetsEnd) {
        finish_lane(lane);
        if (next_strip(&s)) {
          start_lane(&lane, s, lod);
        } else {
          lane = lanes[--active];
        }
        continue;
      }
      if (lane.out == lane.out_end) return bad_walk(lane.strip, lod, "longer than at LoD 0");
      uint32_t* record = pool + lane.id;
      indices[lane.out++] = record[kVertex];
      if (record[kEpoch] != epoch) {
        const uint32_t arcs = record[kArcCount];
        const uint32_t* labels = record + kLabels;
        uint32_t a = 0;
        if (arcs <= 16) {
          while (labels[a] < lod)
            ++a;  // the last label is the last LoD
        } else {
          a = static_cast<uint32_t>(std::lower_bound(labels, labels + arcs, lod) - labels);
        }
        record[kEpoch] = epoch;
        record[kCursor] = labels[arcs + a];
        record[kEnd] = labels[arcs + a + 1];
      }
      if (record[kCursor] == record[kEnd])
        return bad_walk(lane.strip, lod,
                        "a node is visited more often than its successor run allows");
      lane.id = pool[record[kCursor]++];
      if (lane.id != kSetsEnd) __builtin_prefetch(pool + lane.id);
      ++i;
    }
  }
  return Status::ok();
}

Status StripRecovery::recover(uint32_t lod) {
  if (lod >= graph_->lod_count)
    return invalid_input("LoD " + std::to_string(lod) + " out of range (" +
                         std::to_string(graph_->lod_count) + " LoDs)");
  has_state_ = false;
  next_epoch();
  walked_strips_ = walked_indices_ = 0;
  size_t next = 0;
  const size_t strips = count_.size();
  LODBAKE_RETURN_IF_ERROR(walk_strips(lod, [&](uint32_t* strip) {
    for (; next < strips; ++next) {
      if (lod < empty_from_[next]) {
        *strip = static_cast<uint32_t>(next++);
        return true;
      }
      total_ -= count_[next];
      count_[next] = 0;
    }
    return false;
  }));
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
  size_t e = from;
  LODBAKE_RETURN_IF_ERROR(walk_strips(lod, [&](uint32_t* strip) {
    for (; e < to; ++e) {
      const uint32_t s = event_strip_[e];
      if (strip_epoch_[s] == epoch_) continue;
      strip_epoch_[s] = epoch_;
      *strip = s;
      ++e;
      return true;
    }
    return false;
  }));
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

std::vector<std::string> check_recovered_triangles(const StripRecovery& recovery,
                                                   const std::vector<Triangle>& lod_triangles) {
  return compare_strip_triangles(recovery.to_strips(), lod_triangles, "PM");
}

std::string compare_recoveries(const StripRecovery& a, const StripRecovery& b) {
  if (a.strip_count() != b.strip_count()) {
    return "recoveries of " + std::to_string(a.strip_count()) + " and " +
           std::to_string(b.strip_count()) + " strips";
  }
  size_t differing = 0, first = 0;
  for (size_t s = 0; s < a.strip_count(); ++s) {
    const uint32_t* pa = a.indices().data() + a.first(s);
    const uint32_t* pb = b.indices().data() + b.first(s);
    if (a.count(s) == b.count(s) && std::equal(pa, pa + a.count(s), pb)) continue;
    if (differing++ == 0) first = s;
  }
  if (differing == 0) return std::string();
  return std::to_string(differing) + " strips differ, first strip " + std::to_string(first) + " (" +
         std::to_string(a.count(first)) + " against " + std::to_string(b.count(first)) +
         " indices)";
}

}  // namespace lodbake
