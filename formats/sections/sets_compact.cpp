// Compact SETS (codec 1): a lossless recoding of a raw SETS payload, layout
// in docs/format.md "Compact SETS". The graph of Belmonte, Aguado and
// Sancho (ICCS 2006) labels each successor run with the last LoD it is
// valid for; the raw payload spends bits(lod_count) bits on every label
// and bits(n_s + 1) on every successor.
//
// Choices, measured on the Stanford bunny's graph (3495 strips, 106452
// nodes, 239920 arcs, 410346 successors; raw 296 bits per vertex):
// - Every list's last label is lod_count - 1, so a flag bit says "last"
//   and replaces the beginning, arc and node-run counts.
// - A run changes when a vertex of the strip is contracted away:
//   contraction l removes vertex V - l, so a label L is often
//   V - u - 1 for a successor u of the run (71% of the labels that are not
//   last). The candidates are those values of the arc's successors that
//   fit after the previous label; a hit costs 1 + bits(candidates) bits,
//   a miss 1 bit plus the Exp-Golomb gap from the previous label (the
//   gaps' log2 is 12 to 15 on the bunny: labels carry little else).
// - Successors as the zigzag step from the node after the arc's node
//   (entropy 4.2 bits, against 8 to 10 raw); in a node's later arcs, code 0
//   repeats the previous arc's successor at the same index (35% do).
// - Node vertices stay bits(V) wide: PM ids of neighbouring vertices are
//   not close, and the decoder has no mesh to predict them from. They come
//   before the strip's arcs, whose label candidates need them.
// - The decoder rebuilds the graph and writes it with the raw writer, so
//   its output obeys every SETS rule; the encoder refuses raw payloads the
//   raw writer would not write byte for byte (other count widths).
#include "formats/sections/sets_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/sets.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

enum Context : int {
  kNodeCount,
  kBeginningLabel,
  kBeginningNode,
  kSuccessorCount,
  kFirstSuccessor,
  kLaterSuccessor,
  kLabelGap,
  kContextCount
};

constexpr size_t kCandidateSuccessors = 64;

Status bad_compact(const std::string& detail) {
  return malformed_section(kSetsTag, "compact: " + detail);
}

// The labels a successor run of a node predicts (see the file comment):
// distinct V - u - 1 for its first successors' vertices u, between `previous`
// (exclusive, -1 before the first) and the last label (exclusive).
void label_candidates(const uint32_t* successors, size_t count, const SetsGraph& g,
                      int64_t previous, std::vector<uint32_t>* out) {
  out->clear();
  const int64_t last = int64_t{g.lod_count} - 1;
  // Only the first kCandidateSuccessors successors: the distinct-value
  // check is quadratic, and hostile runs may be long.
  for (size_t i = 0; i < count && i < kCandidateSuccessors; ++i) {
    if (successors[i] == kSetsEnd) continue;
    const int64_t c = int64_t{g.vertex_count} - g.node_vertex[successors[i]] - 1;
    if (c <= previous || c >= last) continue;
    bool seen = false;
    for (uint32_t x : *out)
      seen = seen || x == c;
    if (!seen) out->push_back(static_cast<uint32_t>(c));
  }
}

void encode_pass(const SetsGraph& g, CompactStreamWriter* out) {
  const int vertex_bits = bits_for_count(g.vertex_count);
  const uint32_t last = g.lod_count - 1;
  std::vector<uint32_t> candidates;
  for (size_t s = 0; s < g.strip_count(); ++s) {
    const uint32_t n0 = g.node_first[s], n1 = g.node_first[s + 1];
    const uint32_t ns = n1 - n0;
    auto local = [&](uint32_t node) -> int64_t { return node == kSetsEnd ? ns : node - n0; };
    out->golomb(kNodeCount, ns - 1);
    int64_t previous = -1;
    for (uint32_t k = g.beginning_first[s]; k < g.beginning_first[s + 1]; ++k) {
      const uint32_t label = g.beginning_lod[k];
      out->bits(label == last, 1);
      if (label != last) out->golomb(kBeginningLabel, static_cast<uint64_t>(label - previous - 1));
      previous = label;
      out->golomb(kBeginningNode, static_cast<uint64_t>(local(g.beginning_node[k])));
    }
    for (uint32_t n = n0; n < n1; ++n)
      out->bits(g.node_vertex[n], vertex_bits);
    for (uint32_t n = n0; n < n1; ++n) {
      const int64_t next = local(n) + 1;
      previous = -1;
      for (uint32_t a = g.arc_first[n]; a < g.arc_first[n + 1]; ++a) {
        const uint32_t first = g.successor_first[a], count = g.successor_first[a + 1] - first;
        out->golomb(kSuccessorCount, count - 1);
        for (uint32_t j = 0; j < count; ++j) {
          const uint32_t succ = g.successors[first + j];
          const uint64_t step = zigzag64(local(succ) - next);
          if (a == g.arc_first[n]) {
            out->golomb(kFirstSuccessor, step);
          } else {
            const uint32_t before = g.successor_first[a - 1];
            const bool repeat = before + j < first && g.successors[before + j] == succ;
            out->golomb(kLaterSuccessor, repeat ? 0 : 1 + step);
          }
        }
        const uint32_t label = g.arc_lod[a];
        out->bits(label == last, 1);
        if (label != last) {
          label_candidates(g.successors.data() + first, count, g, previous, &candidates);
          size_t hit = candidates.size();
          for (size_t c = 0; c < candidates.size(); ++c) {
            if (candidates[c] == label) hit = c;
          }
          if (!candidates.empty()) {
            out->bits(hit < candidates.size(), 1);
            if (hit < candidates.size()) out->bits(hit, bits_for_count(candidates.size()));
          }
          if (hit == candidates.size())
            out->golomb(kLabelGap, static_cast<uint64_t>(label - previous - 1));
        }
        previous = label;
      }
    }
  }
}

}  // namespace

Result<Bytes> encode_sets_compact(const uint8_t* raw, size_t raw_size) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(SetsGraph graph, decode_sets(raw, raw_size));
    LODBAKE_ASSIGN_OR_RETURN(Bytes canonical, encode_sets(graph));
    LODBAKE_RETURN_IF_ERROR(
        require_canonical_layout(kSetsTag, canonical, raw, raw_size, "count widths"));
    // Sized first: push_back then a range insert trips g++ 12's -Warray-bounds.
    Bytes out(1 + kSetsFixedBytes);
    out[0] = kSetsCompactVersion;
    std::memcpy(out.data() + 1, raw, kSetsFixedBytes);
    CompactStreamWriter stream(kContextCount);
    encode_pass(graph, &stream);
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact SETS");
  }
}

Result<Bytes> decode_sets_compact(const uint8_t* data, size_t size) {
  try {
    LODBAKE_RETURN_IF_ERROR(
        check_compact_start(kSetsTag, data, size, kSetsFixedBytes, kSetsCompactVersion));
    const uint8_t* fixed = data + 1;
    uint32_t f[7] = {};
    std::memcpy(f, fixed, sizeof(f));
    const uint32_t vertex_count = f[0], lod_count = f[1], strips = f[2], beginnings = f[3],
                   nodes = f[4], arcs = f[5], successors = f[6];
    if (lod_count == 0) return bad_compact("lod count 0");
    if (strips > beginnings || strips > nodes || nodes > arcs || arcs > successors)
      return bad_compact("the fixed fields' counts do not nest");
    CompactStreamReader in;
    if (!in.start(fixed + kSetsFixedBytes, size - 1 - kSetsFixedBytes, kContextCount))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    // Each strip's node count, beginning (flag and node), arc (count, one
    // successor, flag) and further successor takes at least one bit.
    const uint64_t min_bits =
        uint64_t{strips} + 2 * uint64_t{beginnings} + 2 * uint64_t{arcs} + uint64_t{successors};
    if (min_bits > in.bits_left()) {
      return bad_compact(string_printf("the counts need at least %" PRIu64 " bits, %" PRIu64
                                       " remain",
                                       min_bits, in.bits_left()));
    }
    SetsGraph g;
    g.vertex_count = vertex_count;
    g.lod_count = lod_count;
    g.beginning_first.reserve(uint64_t{strips} + 1);
    g.node_first.reserve(uint64_t{strips} + 1);
    g.beginning_lod.reserve(beginnings);
    g.beginning_node.reserve(beginnings);
    g.node_vertex.reserve(nodes);
    g.arc_first.reserve(uint64_t{nodes} + 1);
    g.arc_lod.reserve(arcs);
    g.successor_first.reserve(uint64_t{arcs} + 1);
    g.successors.reserve(successors);
    const int vertex_bits = bits_for_count(vertex_count);
    const uint32_t last = lod_count - 1;
    std::vector<uint32_t> candidates;
    uint64_t value = 0;
    auto truncated = [](const char* what, size_t strip) {
      return bad_compact(
          string_printf("truncated or malformed code in the %s of strip %zu", what, strip));
    };
    for (size_t s = 0; s < strips; ++s) {
      if (!in.golomb(kNodeCount, &value)) return truncated("node count", s);
      if (value >= nodes - g.node_vertex.size())
        return bad_compact(string_printf("strip %zu has nodes beyond the header's %u", s, nodes));
      const uint32_t n0 = static_cast<uint32_t>(g.node_vertex.size());
      const uint32_t ns = static_cast<uint32_t>(value + 1);
      // A local node in 0..ns, ns meaning END, as the graph's global id.
      auto global = [&](int64_t local) -> uint32_t {
        return local == ns ? kSetsEnd : n0 + static_cast<uint32_t>(local);
      };
      int64_t previous = -1;
      uint64_t label = 0;
      do {
        if (g.beginning_lod.size() == beginnings)
          return bad_compact(
              string_printf("strip %zu has beginnings beyond the header's %u", s, beginnings));
        uint64_t is_last = 0;
        if (!in.bits(1, &is_last)) return truncated("beginnings", s);
        label = last;
        if (is_last == 0) {
          if (!in.golomb(kBeginningLabel, &value)) return truncated("beginnings", s);
          if (value >= static_cast<uint64_t>(int64_t{last} - previous - 1))
            return bad_compact(string_printf("strip %zu: beginning label out of order", s));
          label = static_cast<uint64_t>(previous + 1) + value;
        }
        previous = static_cast<int64_t>(label);
        if (!in.golomb(kBeginningNode, &value)) return truncated("beginnings", s);
        if (value > ns)
          return bad_compact(string_printf("strip %zu: beginning node past its nodes", s));
        g.beginning_lod.push_back(static_cast<uint32_t>(label));
        g.beginning_node.push_back(global(static_cast<int64_t>(value)));
      } while (label != last);
      g.beginning_first.push_back(static_cast<uint32_t>(g.beginning_lod.size()));
      for (uint32_t n = 0; n < ns; ++n) {
        if (!in.bits(vertex_bits, &value)) return truncated("node vertices", s);
        if (value >= vertex_count)
          return bad_compact(
              string_printf("strip %zu: node vertex %" PRIu64 " out of range", s, value));
        g.node_vertex.push_back(static_cast<uint32_t>(value));
      }
      g.node_first.push_back(n0 + ns);
      for (uint32_t n = 0; n < ns; ++n) {
        const int64_t next = int64_t{n} + 1;
        previous = -1;
        do {
          if (g.arc_lod.size() == arcs)
            return bad_compact(string_printf("strip %zu has arcs beyond the header's %u", s, arcs));
          const bool first_arc = g.arc_lod.size() == g.arc_first.back();
          if (!in.golomb(kSuccessorCount, &value)) return truncated("successor count", s);
          if (value >= successors - g.successors.size())
            return bad_compact(
                string_printf("strip %zu has successors beyond the header's %u", s, successors));
          const size_t count = static_cast<size_t>(value + 1);
          const size_t first = g.successors.size();
          // The previous arc's successors start here (none before the first arc).
          const size_t before = first_arc ? first : g.successor_first[g.successor_first.size() - 2];
          for (size_t j = 0; j < count; ++j) {
            if (!in.golomb(first_arc ? kFirstSuccessor : kLaterSuccessor, &value))
              return truncated("successors", s);
            if (!first_arc && value == 0) {
              if (before + j >= first)
                return bad_compact(string_printf("strip %zu: repeat of a missing successor", s));
              g.successors.push_back(g.successors[before + j]);
              continue;
            }
            const int64_t local = next + unzigzag64(first_arc ? value : value - 1);
            if (local < 0 || local > ns)
              return bad_compact(string_printf("strip %zu: successor past its nodes", s));
            g.successors.push_back(global(local));
          }
          g.successor_first.push_back(static_cast<uint32_t>(g.successors.size()));
          uint64_t is_last = 0;
          if (!in.bits(1, &is_last)) return truncated("arc labels", s);
          label = last;
          if (is_last == 0) {
            label_candidates(g.successors.data() + first, count, g, previous, &candidates);
            uint64_t hit = 0;
            if (!candidates.empty() && !in.bits(1, &hit)) return truncated("arc labels", s);
            if (hit != 0) {
              if (!in.bits(bits_for_count(candidates.size()), &value))
                return truncated("arc labels", s);
              if (value >= candidates.size())
                return bad_compact(string_printf("strip %zu: label candidate out of range", s));
              label = candidates[static_cast<size_t>(value)];
            } else {
              if (!in.golomb(kLabelGap, &value)) return truncated("arc labels", s);
              if (value >= static_cast<uint64_t>(int64_t{last} - previous - 1))
                return bad_compact(string_printf("strip %zu: arc label out of order", s));
              label = static_cast<uint64_t>(previous + 1) + value;
            }
          }
          previous = static_cast<int64_t>(label);
          g.arc_lod.push_back(static_cast<uint32_t>(label));
        } while (label != last);
        g.arc_first.push_back(static_cast<uint32_t>(g.arc_lod.size()));
      }
    }
    return finish_compact_decode(kSetsTag, in, encode_sets(g), fixed, kSetsFixedBytes, "graph");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact SETS");
  }
}

}  // namespace lodbake
