// SETS graph construction (Belmonte, Aguado, Sancho, "Triangle Strip
// Multiresolution Modelling Using Sorted Edges", ICCS 2006, section 3.2).
//
// Choices where the paper is vague:
// - The contraction sequence is the progressive mesh's half-edge collapses
//   in coarsening order, so LoD l has exactly the PM's triangles at
//   full_vertex_count() - l vertices (the collapse's two wing triangles are
//   the windows that become degenerate).
// - A vertex's node is created the first time it appears in the strip (a
//   contraction can bring a vertex into a strip it was not in). Its arcs
//   are recorded with the LoD where they start; a run that is the same as
//   the node's last one is not repeated, even after LoDs where the vertex
//   was absent (the walk never asks then). Labels (the paper's maximum LoD)
//   are the next arc's start - 1, and the last arc's is the last LoD.
// - Node ids are given in order of creation within a strip; arcs in order
//   of LoD. Vertex-to-node lookups scan the few strips each vertex is in.
// - The working sequences hold node ids, not vertices: within a strip a
//   node is one vertex, so the compaction (which only compares ids) is the
//   same, and recording needs no vertex-to-node lookup per index. They sit
//   in one pool, each in its input strip's slot (they only shrink).
// - After a contraction only some nodes can have a new successor run: b's,
//   those before an occurrence of a, and those the compaction removes or
//   leaves before a removal; every other node's last arc is still its run.
//   So a record compares those alone (on the dragon, about 4 of a changed
//   strip's 50 indices), against the last run kept beside the node.
// - Threads: a strip's sequences, nodes, arcs and beginnings depend on its
//   own indices and the contractions alone, and the graph lists them strip
//   by strip. So consecutive ranges of strips are built apart (each replays
//   every contraction on its own strips) and their graphs joined in strip
//   order: the same graph for any number of ranges.
// - Memory: the nodes, arcs and successors are the peak of lodbake-strips;
//   they sit in chunked arrays (no doubling slack, no copy while growing),
//   an arc's successor count is the gap to the next arc's start in
//   successors_, and the replay's state is freed before the graph is
//   assembled, each record array as soon as the graph holds its content.
#include "lib/strips/sets_build.h"

#include <algorithm>
#include <new>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <string>
#include <utility>
#include <vector>

#include "lib/core/parallel.h"
#include "lib/strips/chunked_array.h"
#include "lib/strips/strip_compaction.h"

namespace lodbake {
namespace {

using strips_internal::ChunkedArray;

// Hands the heap's free pages back to the system. The record arrays are
// freed in chunks between live ones, so the allocator keeps them resident,
// and the graph assembled next is allocated beside them: without this the
// resident peak is the freed arrays plus the graph (glibc only; elsewhere
// the allocator decides).
void return_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

constexpr uint32_t kNone = 0xFFFFFFFFu;
// In a sequence, the node a contraction's kept vertex gets if it survives.
constexpr uint32_t kNewNode = 0xFFFFFFFEu;

// The graph of strips [range.begin, range.end): its strip s is the input's
// range.begin + s.
class Builder {
 public:
  Builder(const TriangleStrips& strips, IndexRange range, const ProgressiveMesh& pm,
          SetsBuildStats* stats)
      : strips_(strips), range_(range), pm_(pm), stats_(stats) {}

  SetsGraph run() {
    const size_t strip_count = range_.end - range_.begin;
    // Sequences only shrink: each keeps its strip's slot in one pool.
    const uint32_t pool_begin = strips_.first[range_.begin];
    pool_.assign(strips_.indices.begin() + pool_begin,
                 strips_.indices.begin() + strips_.first[range_.end]);
    sequence_first_.resize(strip_count);
    sequence_size_.resize(strip_count);
    last_beginning_.assign(strip_count, kNone);
    vertex_nodes_.resize(pm_.full_vertex_count());
    for (uint32_t s = 0; s < strip_count; ++s) {
      sequence_first_[s] = strips_.first[range_.begin + s] - pool_begin;
      sequence_size_[s] = strips_.first[range_.begin + s + 1] - strips_.first[range_.begin + s];
      for (uint32_t& v : sequence(s))
        v = node_of(s, v);
      record(s, 0, nullptr);
    }
    const uint32_t base = static_cast<uint32_t>(pm_.base.vertex_count());
    const uint32_t splits = static_cast<uint32_t>(pm_.splits.size());
    for (uint32_t lod = 1; lod <= splits; ++lod) {
      const uint32_t k = splits - lod;
      contract(lod, base + k, pm_.splits[k].vs);
    }
    stats_->contractions = splits;
    for (uint32_t size : sequence_size_)
      stats_->emptied_strips += size == 0;
    release_replay();
    return_free_memory();
    return assemble(splits + 1);
  }

 private:
  // Its successors are successors_[succ_begin, the next arc's succ_begin).
  struct Arc {
    uint32_t node, start, succ_begin;
  };
  // A strip's current sequence in pool_.
  struct Sequence {
    uint32_t* data;
    size_t count;
    uint32_t* begin() const { return data; }
    uint32_t* end() const { return data + count; }
    size_t size() const { return count; }
    bool empty() const { return count == 0; }
    uint32_t& operator[](size_t i) const { return data[i]; }
  };
  Sequence sequence(uint32_t s) { return {pool_.data() + sequence_first_[s], sequence_size_[s]}; }
  // What a record needs of a node, side by side (one cache line or two
  // instead of the far-apart arc and successors): its last arc's run, by
  // length (0: no arc yet), start in successors_ and first two successors
  // (most runs have one or two), and scratch that is zero between records.
  struct Node {
    uint32_t last_count = 0, last_succ = 0;
    uint32_t last_head[2] = {kNone, kNone};
    uint32_t count = 0, offset = 0;
  };

  uint32_t node_of(uint32_t strip, uint32_t vertex) {
    const uint32_t found = find_node(strip, vertex);
    if (found != kNone) return found;
    const uint32_t node = static_cast<uint32_t>(node_link_.size());
    node_link_.push_back({strip, kNone});
    node_vertex_.push_back(vertex);
    node_.push_back(Node());
    selected_.push_back(0);
    VertexNodes& list = vertex_nodes_[vertex];
    (list.first == kNone ? list.first : node_link_[list.last].next) = node;
    list.last = node;
    return node;
  }

  // b's node in strip s, or kNone when b has none there yet.
  uint32_t find_node(uint32_t strip, uint32_t vertex) const {
    for (uint32_t n = vertex_nodes_[vertex].first; n != kNone; n = node_link_[n].next)
      if (node_link_[n].strip == strip) return n;
    return kNone;
  }

  void contract(uint32_t lod, uint32_t a, uint32_t b) {
    // a's list is taken: a never appears again, and b's list grows.
    uint32_t next = vertex_nodes_[a].first;
    vertex_nodes_[a] = VertexNodes();
    while (next != kNone) {
      const uint32_t from = next;
      const uint32_t s = node_link_[from].strip;
      next = node_link_[from].next;
      const Sequence q = sequence(s);
      // b's node is created only if b survives the compaction (as the first
      // record of b in this strip would); until then kNewNode stands for it.
      const uint32_t existing = find_node(s, b);
      const uint32_t to = existing == kNone ? kNewNode : existing;
      // The nodes whose successor runs may change: b's, those before an
      // occurrence of a, and what the compaction notes.
      changed_.clear();
      bool found = false;
      for (size_t i = 0; i < q.size(); ++i) {
        if (q[i] == from) {
          q[i] = to;
          found = true;
          if (i > 0) changed_.push_back(q[i - 1]);
        }
      }
      if (!found) continue;  // a left this strip in an earlier compaction
      const size_t before = q.size();
      sequence_size_[s] = static_cast<uint32_t>(compact_strip(q.data, q.size(), &changed_));
      const Sequence kept_q = sequence(s);
      uint32_t kept = to;
      if (to == kNewNode && std::find(kept_q.begin(), kept_q.end(), kNewNode) != kept_q.end()) {
        kept = node_of(s, b);
        std::replace(kept_q.begin(), kept_q.end(), kNewNode, kept);
      }
      changed_.push_back(kept);
      stats_->removed_indices += before - kept_q.size();
      ++stats_->strip_updates;
      record(s, lod, &changed_);
    }
  }

  // Records strip s's sequence at `lod`: a new beginning and new arcs where
  // they differ from the last recorded ones. Every node of the strip holds
  // its current run as its last arc after each record, so only the nodes in
  // `changed` (all when null) can need a new arc.
  void record(uint32_t s, uint32_t lod, const std::vector<uint32_t>* changed) {
    const Sequence q = sequence(s);
    const uint32_t first = q.empty() ? kNone : q[0];
    if (first != last_beginning_[s]) {
      beginnings_.push_back({s, lod, first});
      last_beginning_[s] = first;
    }
    if (q.empty()) return;
    if (changed == nullptr) {
      count_runs(q, [](uint32_t) { return true; });
    } else {
      for (uint32_t node : *changed)
        if (node < kNewNode) selected_[node] = 1;
      count_runs(q, [&](uint32_t node) { return selected_[node] != 0; });
      for (uint32_t node : *changed)
        if (node < kNewNode) selected_[node] = 0;
    }
    for (uint32_t node : touched_) {
      Node& nd = node_[node];
      const uint32_t count = nd.count;
      const uint32_t* run = runs_.data() + (nd.offset - count);
      nd.count = 0;
      if (nd.last_count == count && run[0] == nd.last_head[0] &&
          (count == 1 || run[1] == nd.last_head[1]) && same_tail(run, count, nd.last_succ))
        continue;
      nd.last_count = count;
      nd.last_succ = static_cast<uint32_t>(successors_.size());
      nd.last_head[0] = run[0];
      nd.last_head[1] = count > 1 ? run[1] : kNone;
      arcs_.push_back({node, lod, static_cast<uint32_t>(successors_.size())});
      for (uint32_t i = 0; i < count; ++i)
        successors_.push_back(run[i]);
    }
  }

  // Whether run[2, count) equals the stored successors from at + 2.
  bool same_tail(const uint32_t* run, uint32_t count, uint32_t at) const {
    for (uint32_t i = 2; i < count; ++i)
      if (run[i] != successors_[at + i]) return false;
    return true;
  }

  uint32_t succ_end(size_t arc) const {
    return static_cast<uint32_t>(arc + 1 < arcs_.size() ? arcs_[arc + 1].succ_begin
                                                        : successors_.size());
  }

  // The replay's state, not needed to assemble the graph.
  void release_replay() {
    std::vector<uint32_t>().swap(pool_);
    std::vector<uint32_t>().swap(sequence_first_);
    std::vector<uint32_t>().swap(sequence_size_);
    std::vector<uint32_t>().swap(last_beginning_);
    std::vector<VertexNodes>().swap(vertex_nodes_);
    node_.release();
    selected_.release();
    std::vector<uint32_t>().swap(runs_);
    std::vector<uint32_t>().swap(touched_);
    std::vector<uint32_t>().swap(changed_);
  }

  // The successor runs of q's nodes that pass `wanted`: touched_ lists them
  // (in order of first occurrence), node n's run is runs_[node_[n].offset -
  // node_[n].count, node_[n].offset).
  template <typename Wanted>
  void count_runs(const Sequence& q, Wanted wanted) {
    touched_.clear();
    size_t total = 0;
    for (uint32_t node : q) {
      if (!wanted(node)) continue;
      ++total;
      if (node_[node].count++ == 0) touched_.push_back(node);
    }
    uint32_t running = 0;
    for (uint32_t node : touched_) {
      node_[node].offset = running;
      running += node_[node].count;
    }
    runs_.resize(total);
    for (size_t i = 0; i < q.size(); ++i)
      if (wanted(q[i])) runs_[node_[q[i]].offset++] = i + 1 < q.size() ? q[i + 1] : kNone;
  }

  SetsGraph assemble(uint32_t lod_count) {
    SetsGraph g;
    const size_t strip_count = range_.end - range_.begin;
    g.vertex_count = static_cast<uint32_t>(pm_.full_vertex_count());
    g.lod_count = lod_count;
    // Nodes grouped by strip, in creation order.
    const size_t nodes = node_link_.size();
    g.node_first.assign(strip_count + 1, 0);
    for (size_t n = 0; n < nodes; ++n)
      ++g.node_first[node_link_[n].strip + 1];
    for (size_t s = 0; s < strip_count; ++s)
      g.node_first[s + 1] += g.node_first[s];
    std::vector<uint32_t> fill(g.node_first.begin(), g.node_first.end() - 1);
    std::vector<uint32_t> new_id(nodes);
    for (size_t n = 0; n < nodes; ++n)
      new_id[n] = fill[node_link_[n].strip]++;
    node_link_.release();
    auto remap = [&](uint32_t node) { return node == kNone ? kSetsEnd : new_id[node]; };
    g.node_vertex.resize(nodes);
    for (size_t n = 0; n < nodes; ++n)
      g.node_vertex[new_id[n]] = node_vertex_[n];
    node_vertex_.release();
    // Arcs grouped by node, in LoD order (they were appended in LoD order).
    g.arc_first.assign(nodes + 1, 0);
    for (size_t a = 0; a < arcs_.size(); ++a)
      ++g.arc_first[new_id[arcs_[a].node] + 1];
    for (size_t n = 0; n < nodes; ++n)
      g.arc_first[n + 1] += g.arc_first[n];
    // Each arc goes to its node's next slot k; an arc's label is the next
    // arc's start - 1. Its node is not needed after this: it keeps k.
    fill.assign(g.arc_first.begin(), g.arc_first.end() - 1);
    g.arc_lod.assign(arcs_.size(), lod_count - 1);
    g.successor_first.assign(arcs_.size() + 1, 0);
    for (size_t a = 0; a < arcs_.size(); ++a) {
      const uint32_t n = new_id[arcs_[a].node];
      const uint32_t k = fill[n]++;
      if (k > g.arc_first[n]) g.arc_lod[k - 1] = arcs_[a].start - 1;
      g.successor_first[k + 1] = succ_end(a) - arcs_[a].succ_begin;
      arcs_[a].node = k;
    }
    for (size_t k = 0; k < arcs_.size(); ++k)
      g.successor_first[k + 1] += g.successor_first[k];
    g.successors.resize(successors_.size());
    for (size_t a = 0; a < arcs_.size(); ++a) {
      uint32_t* out = g.successors.data() + g.successor_first[arcs_[a].node];
      for (uint32_t i = arcs_[a].succ_begin, end = succ_end(a); i < end; ++i)
        *out++ = remap(successors_[i]);
    }
    arcs_.release();
    successors_.release();
    return_free_memory();
    // Beginnings grouped by strip, in LoD order.
    g.beginning_first.assign(strip_count + 1, 0);
    for (size_t i = 0; i < beginnings_.size(); ++i)
      ++g.beginning_first[beginnings_[i].strip + 1];
    for (size_t s = 0; s < strip_count; ++s)
      g.beginning_first[s + 1] += g.beginning_first[s];
    std::vector<uint32_t> border(beginnings_.size());
    fill.assign(g.beginning_first.begin(), g.beginning_first.end() - 1);
    for (size_t i = 0; i < beginnings_.size(); ++i)
      border[fill[beginnings_[i].strip]++] = i;
    g.beginning_lod.resize(beginnings_.size());
    g.beginning_node.resize(beginnings_.size());
    for (size_t s = 0; s < strip_count; ++s) {
      for (uint32_t k = g.beginning_first[s]; k < g.beginning_first[s + 1]; ++k) {
        const Beginning& b = beginnings_[border[k]];
        g.beginning_node[k] = remap(b.node);
        g.beginning_lod[k] =
            k + 1 < g.beginning_first[s + 1] ? beginnings_[border[k + 1]].start - 1 : lod_count - 1;
      }
    }
    return g;
  }

  struct Beginning {
    uint32_t strip, start, node;
  };
  const TriangleStrips& strips_;
  const IndexRange range_;
  const ProgressiveMesh& pm_;
  SetsBuildStats* stats_;
  std::vector<uint32_t> pool_;  // the strips' sequences (node ids)
  std::vector<uint32_t> sequence_first_, sequence_size_;
  std::vector<uint32_t> last_beginning_;
  // A vertex's nodes, one per strip it is in, in order of creation: a list
  // threaded through the nodes (8 bytes a node and a vertex, where a vector
  // per vertex took a header, a heap block and its slack).
  struct VertexNodes {
    uint32_t first = kNone, last = kNone;
  };
  struct NodeLink {
    uint32_t strip;
    uint32_t next;  // the vertex's next node, kNone at the end
  };
  std::vector<VertexNodes> vertex_nodes_;
  ChunkedArray<NodeLink> node_link_;
  ChunkedArray<uint32_t> node_vertex_;
  ChunkedArray<Node> node_;
  // Per node, scratch zero between records: one byte, as it is read for
  // every index of a changed strip.
  ChunkedArray<uint8_t> selected_;
  std::vector<uint32_t> runs_, touched_, changed_;
  ChunkedArray<Arc> arcs_;
  ChunkedArray<uint32_t> successors_;
  ChunkedArray<Beginning> beginnings_;
};

// Appends `part`, the graph of the strips after `all`'s, to `all`.
void join(SetsGraph* all, const SetsGraph& part) {
  const uint32_t nodes = static_cast<uint32_t>(all->node_vertex.size());
  auto shifted = [nodes](uint32_t node) { return node == kSetsEnd ? node : node + nodes; };
  auto append_offsets = [](std::vector<uint32_t>* to, const std::vector<uint32_t>& from) {
    const uint32_t base = to->back();
    for (size_t i = 1; i < from.size(); ++i)
      to->push_back(base + from[i]);
  };
  append_offsets(&all->beginning_first, part.beginning_first);
  all->beginning_lod.insert(all->beginning_lod.end(), part.beginning_lod.begin(),
                            part.beginning_lod.end());
  for (uint32_t node : part.beginning_node)
    all->beginning_node.push_back(shifted(node));
  append_offsets(&all->node_first, part.node_first);
  all->node_vertex.insert(all->node_vertex.end(), part.node_vertex.begin(), part.node_vertex.end());
  append_offsets(&all->arc_first, part.arc_first);
  all->arc_lod.insert(all->arc_lod.end(), part.arc_lod.begin(), part.arc_lod.end());
  append_offsets(&all->successor_first, part.successor_first);
  for (uint32_t node : part.successors)
    all->successors.push_back(shifted(node));
}

// Below this many strips per range, a thread's replay of every contraction
// costs more than its share of the strips saves.
constexpr size_t kMinStripsPerPart = 512;

// The p-th of `parts` consecutive ranges of strips holding about as many
// indices each (a strip's work grows with its length): the strips whose
// first index lies in the p-th near-equal piece of the indices.
IndexRange strip_range(const TriangleStrips& strips, size_t parts, size_t p) {
  const size_t count = strips.strip_count();
  if (count == 0) return {0, 0};
  const IndexRange indices = part_range(strips.indices.size(), parts, p);
  auto first_at = [&](size_t index) {
    return static_cast<size_t>(
        std::lower_bound(strips.first.begin(), strips.first.begin() + count, index) -
        strips.first.begin());
  };
  return {first_at(indices.begin), p + 1 == parts ? count : first_at(indices.end)};
}

SetsGraph build_graph(const TriangleStrips& strips, const ProgressiveMesh& pm, unsigned threads,
                      SetsBuildStats* stats) {
  const ParallelScope scope(threads);
  const size_t parts = scope.parts(strips.strip_count(), kMinStripsPerPart);
  std::vector<SetsGraph> graphs(parts);
  std::vector<SetsBuildStats> part_stats(parts);
  scope.for_each_part(parts, [&](size_t p) {
    graphs[p] = Builder(strips, strip_range(strips, parts, p), pm, &part_stats[p]).run();
  });
  SetsGraph graph = std::move(graphs[0]);
  *stats = part_stats[0];
  // Joined into exact capacities: growing by doubling would hold up to
  // three times the graph while it grows.
  auto reserve = [&](std::vector<uint32_t>* all, auto member, bool offsets) {
    size_t total = all->size();
    for (size_t p = 1; p < parts; ++p)
      total += (graphs[p].*member).size() - (offsets ? 1 : 0);
    all->reserve(total);
  };
  reserve(&graph.beginning_first, &SetsGraph::beginning_first, true);
  reserve(&graph.beginning_lod, &SetsGraph::beginning_lod, false);
  reserve(&graph.beginning_node, &SetsGraph::beginning_node, false);
  reserve(&graph.node_first, &SetsGraph::node_first, true);
  reserve(&graph.node_vertex, &SetsGraph::node_vertex, false);
  reserve(&graph.arc_first, &SetsGraph::arc_first, true);
  reserve(&graph.arc_lod, &SetsGraph::arc_lod, false);
  reserve(&graph.successor_first, &SetsGraph::successor_first, true);
  reserve(&graph.successors, &SetsGraph::successors, false);
  for (size_t p = 1; p < parts; ++p) {
    join(&graph, graphs[p]);
    graphs[p] = SetsGraph();
    stats->strip_updates += part_stats[p].strip_updates;
    stats->removed_indices += part_stats[p].removed_indices;
    stats->emptied_strips += part_stats[p].emptied_strips;
  }
  return graph;
}

}  // namespace

Result<SetsGraph> build_sets(const TriangleStrips& strips, const ProgressiveMesh& pm,
                             SetsBuildStats* stats, unsigned threads) {
  const size_t full = pm.full_vertex_count();
  if (strips.vertex_count != full)
    return invalid_input("the strips index " + std::to_string(strips.vertex_count) +
                         " vertices, the progressive mesh has " + std::to_string(full));
  if (full >= kSetsEnd) return invalid_input("more than 2^32 - 2 vertices");
  for (size_t k = 0; k < pm.splits.size(); ++k) {
    if (pm.splits[k].vs >= pm.base.vertex_count() + k)
      return invalid_input("split " + std::to_string(k) + " splits vertex " +
                           std::to_string(pm.splits[k].vs) + ", which does not exist yet");
  }
  for (size_t s = 0; s < strips.strip_count(); ++s)
    if (strips.first[s + 1] <= strips.first[s])
      return invalid_input("strip " + std::to_string(s) + " is empty");
  for (uint32_t v : strips.indices)
    if (v >= full) return invalid_input("strip index " + std::to_string(v) + " out of range");
  try {
    SetsBuildStats local;
    SetsGraph graph = build_graph(strips, pm, threads, &local);
    if (stats != nullptr) *stats = local;
    return graph;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory building the SETS graph");
  }
}

}  // namespace lodbake
