// SETS section codec and checks: the strip graph of Belmonte, Aguado and
// Sancho, "Triangle Strip Multiresolution Modelling Using Sorted Edges"
// (ICCS 2006), byte layout in docs/format.md "SETS".
//
// Choices where the paper is vague (it describes an in-memory layout only):
// - Node ids are local to their strip in the file, so a successor costs
//   bits_for_count(strip's nodes + 1) bits (the extra value is END), not a
//   global id; vertices cost bits_for_count(vertex count) once per node.
// - Structure of arrays in one LSB-first bit stream: the per-strip counts,
//   then every beginning, every node, every arc, every successor. Counts are
//   stored minus one at the width of the largest (nothing is empty: a strip
//   has a node and a beginning, a node an arc, an arc a successor), which
//   also bounds every count by the payload size before allocation.
// - Labels are absolute LoDs at bits_for_count(lod_count) bits; the last
//   label of every list is lod_count - 1, so the search for "first label >=
//   l" always succeeds and the format has one canonical form.
#include "formats/sections/sets.h"

#include <algorithm>
#include <cinttypes>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_sets(const std::string& detail) {
  return malformed_section(kSetsTag, detail);
}

// Checks that `first` is a non-decreasing offset array over `total` entries
// with every range holding at least one entry.
Status check_ranges(const std::vector<uint32_t>& first, size_t total, const char* what,
                    const char* owner) {
  if (first.empty() || first.front() != 0 || first.back() != total)
    return invalid_input(string_printf("%s offsets do not cover the %zu %s", owner, total, what));
  for (size_t i = 0; i + 1 < first.size(); ++i) {
    if (first[i + 1] <= first[i])
      return invalid_input(string_printf("%s %zu has no %s", owner, i, what));
  }
  return Status::ok();
}

Status check_labels(const std::vector<uint32_t>& labels, const std::vector<uint32_t>& first,
                    uint32_t lod_count, const char* what) {
  for (size_t i = 0; i + 1 < first.size(); ++i) {
    for (uint32_t k = first[i]; k < first[i + 1]; ++k) {
      if (labels[k] >= lod_count)
        return invalid_input(string_printf("%s %zu: label %u out of range (%u LoDs)", what, i,
                                           labels[k], lod_count));
      if (k > first[i] && labels[k] <= labels[k - 1])
        return invalid_input(string_printf("%s %zu: labels not increasing (%u after %u)", what, i,
                                           labels[k], labels[k - 1]));
    }
    if (labels[first[i + 1] - 1] != lod_count - 1)
      return invalid_input(string_printf("%s %zu: last label %u, must be the last LoD %u", what, i,
                                         labels[first[i + 1] - 1], lod_count - 1));
  }
  return Status::ok();
}

// First entry of [begin, end) whose label is >= lod (the lists end at the
// last LoD, so one exists for any lod < lod_count).
uint32_t find_label(const std::vector<uint32_t>& labels, uint32_t begin, uint32_t end,
                    uint32_t lod) {
  return static_cast<uint32_t>(std::lower_bound(labels.begin() + begin, labels.begin() + end, lod) -
                               labels.begin());
}

uint8_t count_bits(uint64_t largest_minus_one) {
  return static_cast<uint8_t>(bits_for_count(largest_minus_one + 1));
}

uint32_t max_gap(const std::vector<uint32_t>& first) {
  uint32_t gap = 1;
  for (size_t i = 0; i + 1 < first.size(); ++i)
    gap = std::max(gap, first[i + 1] - first[i]);
  return gap;
}

Status check_fixed(const SetsSummary& s, size_t size) {
  const uint64_t stream_bits = uint64_t{size - kSetsFixedBytes} * 8;
  if (s.lod_count == 0) return bad_sets("lod count 0, at least 1 (the full mesh)");
  if (s.strip_count == 0 && (s.beginning_count | s.node_count | s.arc_count | s.successor_count))
    return bad_sets("no strips but nonzero node, arc or successor counts");
  if (s.strip_count > s.beginning_count || s.strip_count > s.node_count ||
      s.node_count > s.arc_count || s.arc_count > s.successor_count)
    return bad_sets(string_printf(
        "counts do not nest: %u strips, %u beginnings, %u nodes, %u arcs, %u successors",
        s.strip_count, s.beginning_count, s.node_count, s.arc_count, s.successor_count));
  if (s.successor_count > stream_bits || s.beginning_count > stream_bits)
    return bad_sets(string_printf("%u successors and %u beginnings need more than the %" PRIu64
                                  " bits after the fixed fields",
                                  s.successor_count, s.beginning_count, stream_bits));
  for (uint8_t bits : {s.beginnings_bits, s.nodes_bits, s.arcs_bits, s.successors_bits})
    if (bits > 32) return bad_sets(string_printf("count width %u above 32", bits));
  return Status::ok();
}

Result<SetsSummary> parse_fixed(const uint8_t* data, size_t size) {
  ByteReader reader(data, size);
  SetsSummary s;
  if (!reader.read(&s.vertex_count) || !reader.read(&s.lod_count) || !reader.read(&s.strip_count) ||
      !reader.read(&s.beginning_count) || !reader.read(&s.node_count) ||
      !reader.read(&s.arc_count) || !reader.read(&s.successor_count) ||
      !reader.read(&s.beginnings_bits) || !reader.read(&s.nodes_bits) ||
      !reader.read(&s.arcs_bits) || !reader.read(&s.successors_bits)) {
    return bad_sets(
        string_printf("payload has %zu bytes, the fixed fields need %zu", size, kSetsFixedBytes));
  }
  LODBAKE_RETURN_IF_ERROR(check_fixed(s, size));
  return s;
}

// Reads one value or fails naming what was being read.
class StreamReader {
 public:
  StreamReader(const uint8_t* data, size_t size) : bits_(data, size) {}
  Status read(int width, uint32_t* out, const char* what, uint64_t index) {
    if (!bits_.read(width, out))
      return bad_sets(string_printf("the stream ends inside %s %" PRIu64, what, index));
    return Status::ok();
  }
  const BitReader& bits() const { return bits_; }

 private:
  BitReader bits_;
};

Status decode_stream(const uint8_t* data, size_t size, const SetsSummary& s, SetsGraph* g) {
  StreamReader in(data + kSetsFixedBytes, size - kSetsFixedBytes);
  g->vertex_count = s.vertex_count;
  g->lod_count = s.lod_count;
  g->beginning_first.reserve(uint64_t{s.strip_count} + 1);
  g->node_first.reserve(uint64_t{s.strip_count} + 1);
  uint64_t beginnings = 0, nodes = 0;
  for (uint32_t i = 0; i < s.strip_count; ++i) {
    uint32_t b = 0, n = 0;
    LODBAKE_RETURN_IF_ERROR(in.read(s.beginnings_bits, &b, "strip", i));
    LODBAKE_RETURN_IF_ERROR(in.read(s.nodes_bits, &n, "strip", i));
    beginnings += uint64_t{b} + 1;
    nodes += uint64_t{n} + 1;
    if (beginnings > s.beginning_count || nodes > s.node_count)
      return bad_sets(string_printf("strip %u runs past the header's %u beginnings or %u nodes", i,
                                    s.beginning_count, s.node_count));
    g->beginning_first.push_back(static_cast<uint32_t>(beginnings));
    g->node_first.push_back(static_cast<uint32_t>(nodes));
  }
  if (beginnings != s.beginning_count || nodes != s.node_count)
    return bad_sets(string_printf("strips hold %" PRIu64 " beginnings and %" PRIu64
                                  " nodes, the header has %u and %u",
                                  beginnings, nodes, s.beginning_count, s.node_count));
  const int lod_bits = bits_for_count(s.lod_count);
  // Local node ids (kSetsEnd as the strip's node count) become global ones.
  auto global_node = [&](uint32_t strip, uint32_t local, uint32_t* out) {
    const uint32_t count = g->node_first[strip + 1] - g->node_first[strip];
    if (local > count)
      return bad_sets(string_printf("strip %u names node %u, it has %u", strip, local, count));
    *out = local == count ? kSetsEnd : g->node_first[strip] + local;
    return Status::ok();
  };
  g->beginning_lod.resize(s.beginning_count);
  g->beginning_node.resize(s.beginning_count);
  for (uint32_t strip = 0; strip < s.strip_count; ++strip) {
    const int width = bits_for_count(uint64_t{g->node_first[strip + 1] - g->node_first[strip]} + 1);
    for (uint32_t k = g->beginning_first[strip]; k < g->beginning_first[strip + 1]; ++k) {
      uint32_t local = 0;
      LODBAKE_RETURN_IF_ERROR(in.read(lod_bits, &g->beginning_lod[k], "beginning", k));
      LODBAKE_RETURN_IF_ERROR(in.read(width, &local, "beginning", k));
      LODBAKE_RETURN_IF_ERROR(global_node(strip, local, &g->beginning_node[k]));
    }
  }
  g->node_vertex.resize(s.node_count);
  g->arc_first.reserve(uint64_t{s.node_count} + 1);
  const int vertex_bits = bits_for_count(s.vertex_count);
  uint64_t arcs = 0;
  for (uint32_t n = 0; n < s.node_count; ++n) {
    uint32_t count = 0;
    LODBAKE_RETURN_IF_ERROR(in.read(vertex_bits, &g->node_vertex[n], "node", n));
    LODBAKE_RETURN_IF_ERROR(in.read(s.arcs_bits, &count, "node", n));
    arcs += uint64_t{count} + 1;
    if (arcs > s.arc_count)
      return bad_sets(string_printf("node %u runs past the header's %u arcs", n, s.arc_count));
    g->arc_first.push_back(static_cast<uint32_t>(arcs));
  }
  if (arcs != s.arc_count)
    return bad_sets(
        string_printf("nodes hold %" PRIu64 " arcs, the header has %u", arcs, s.arc_count));
  g->arc_lod.resize(s.arc_count);
  g->successor_first.reserve(uint64_t{s.arc_count} + 1);
  uint64_t successors = 0;
  for (uint32_t a = 0; a < s.arc_count; ++a) {
    uint32_t count = 0;
    LODBAKE_RETURN_IF_ERROR(in.read(lod_bits, &g->arc_lod[a], "arc", a));
    LODBAKE_RETURN_IF_ERROR(in.read(s.successors_bits, &count, "arc", a));
    successors += uint64_t{count} + 1;
    if (successors > s.successor_count)
      return bad_sets(
          string_printf("arc %u runs past the header's %u successors", a, s.successor_count));
    g->successor_first.push_back(static_cast<uint32_t>(successors));
  }
  if (successors != s.successor_count)
    return bad_sets(string_printf("arcs hold %" PRIu64 " successors, the header has %u", successors,
                                  s.successor_count));
  g->successors.resize(s.successor_count);
  for (uint32_t strip = 0; strip < s.strip_count; ++strip) {
    const uint32_t n0 = g->node_first[strip], n1 = g->node_first[strip + 1];
    const int width = bits_for_count(uint64_t{n1 - n0} + 1);
    for (uint32_t k = g->successor_first[g->arc_first[n0]];
         k < g->successor_first[g->arc_first[n1]]; ++k) {
      uint32_t local = 0;
      LODBAKE_RETURN_IF_ERROR(in.read(width, &local, "successor", k));
      LODBAKE_RETURN_IF_ERROR(global_node(strip, local, &g->successors[k]));
    }
  }
  if (in.bits().bytes_consumed() != size - kSetsFixedBytes)
    return bad_sets(string_printf("%zu trailing bytes after the stream",
                                  size - kSetsFixedBytes - in.bits().bytes_consumed()));
  if (!in.bits().padding_is_zero()) return bad_sets("nonzero padding bits after the stream");
  return Status::ok();
}

}  // namespace

Status check_sets_structure(const SetsGraph& g) {
  const size_t strips = g.strip_count();
  if (g.lod_count == 0) return invalid_input("lod count 0");
  if (g.beginning_first.size() != strips + 1 || g.beginning_node.size() != g.beginning_lod.size() ||
      g.arc_first.size() != g.node_count() + 1 || g.successor_first.size() != g.arc_count() + 1)
    return invalid_input("array sizes do not agree");
  LODBAKE_RETURN_IF_ERROR(
      check_ranges(g.beginning_first, g.beginning_lod.size(), "beginnings", "strip"));
  LODBAKE_RETURN_IF_ERROR(check_ranges(g.node_first, g.node_count(), "nodes", "strip"));
  LODBAKE_RETURN_IF_ERROR(check_ranges(g.arc_first, g.arc_count(), "arcs", "node"));
  LODBAKE_RETURN_IF_ERROR(
      check_ranges(g.successor_first, g.successors.size(), "successors", "arc"));
  LODBAKE_RETURN_IF_ERROR(
      check_labels(g.beginning_lod, g.beginning_first, g.lod_count, "beginnings of strip"));
  LODBAKE_RETURN_IF_ERROR(check_labels(g.arc_lod, g.arc_first, g.lod_count, "arcs of node"));
  for (size_t n = 0; n < g.node_count(); ++n) {
    if (g.node_vertex[n] >= g.vertex_count)
      return invalid_input(string_printf("node %zu: vertex %u out of range (%u vertices)", n,
                                         g.node_vertex[n], g.vertex_count));
  }
  for (size_t s = 0; s < strips; ++s) {
    const uint32_t n0 = g.node_first[s], n1 = g.node_first[s + 1];
    auto in_strip = [&](uint32_t node) { return node == kSetsEnd || (node >= n0 && node < n1); };
    for (uint32_t k = g.beginning_first[s]; k < g.beginning_first[s + 1]; ++k)
      if (!in_strip(g.beginning_node[k]))
        return invalid_input(string_printf("strip %zu: beginning %u names node %u of another strip",
                                           s, k, g.beginning_node[k]));
    for (uint32_t k = g.successor_first[g.arc_first[n0]]; k < g.successor_first[g.arc_first[n1]];
         ++k)
      if (!in_strip(g.successors[k]))
        return invalid_input(string_printf("strip %zu: successor %u names node %u of another strip",
                                           s, k, g.successors[k]));
  }
  return Status::ok();
}

Result<Bytes> encode_sets(const SetsGraph& g) {
  Status structure = check_sets_structure(g);
  if (!structure.is_ok()) return invalid_input("cannot encode SETS: " + structure.message());
  if (g.successors.size() > UINT32_MAX)
    return invalid_input("cannot encode SETS: more than 2^32 - 1 successors");
  try {
    Bytes out;
    ByteWriter writer(&out);
    SetsSummary s;
    s.beginnings_bits = count_bits(max_gap(g.beginning_first) - 1);
    s.nodes_bits = count_bits(max_gap(g.node_first) - 1);
    s.arcs_bits = count_bits(max_gap(g.arc_first) - 1);
    s.successors_bits = count_bits(max_gap(g.successor_first) - 1);
    writer.write(g.vertex_count);
    writer.write(g.lod_count);
    writer.write(static_cast<uint32_t>(g.strip_count()));
    writer.write(static_cast<uint32_t>(g.beginning_lod.size()));
    writer.write(static_cast<uint32_t>(g.node_count()));
    writer.write(static_cast<uint32_t>(g.arc_count()));
    writer.write(static_cast<uint32_t>(g.successors.size()));
    for (uint8_t b : {s.beginnings_bits, s.nodes_bits, s.arcs_bits, s.successors_bits})
      writer.write(b);
    BitWriter bits(&out);
    for (size_t i = 0; i < g.strip_count(); ++i) {
      bits.write(g.beginning_first[i + 1] - g.beginning_first[i] - 1, s.beginnings_bits);
      bits.write(g.node_first[i + 1] - g.node_first[i] - 1, s.nodes_bits);
    }
    const int lod_bits = bits_for_count(g.lod_count);
    auto local = [&](size_t strip, uint32_t node) {
      return node == kSetsEnd ? g.node_first[strip + 1] - g.node_first[strip]
                              : node - g.node_first[strip];
    };
    for (size_t strip = 0; strip < g.strip_count(); ++strip) {
      const int width = bits_for_count(uint64_t{g.node_first[strip + 1] - g.node_first[strip]} + 1);
      for (uint32_t k = g.beginning_first[strip]; k < g.beginning_first[strip + 1]; ++k) {
        bits.write(g.beginning_lod[k], lod_bits);
        bits.write(local(strip, g.beginning_node[k]), width);
      }
    }
    const int vertex_bits = bits_for_count(g.vertex_count);
    for (size_t n = 0; n < g.node_count(); ++n) {
      bits.write(g.node_vertex[n], vertex_bits);
      bits.write(g.arc_first[n + 1] - g.arc_first[n] - 1, s.arcs_bits);
    }
    for (size_t a = 0; a < g.arc_count(); ++a) {
      bits.write(g.arc_lod[a], lod_bits);
      bits.write(g.successor_first[a + 1] - g.successor_first[a] - 1, s.successors_bits);
    }
    for (size_t strip = 0; strip < g.strip_count(); ++strip) {
      const uint32_t n0 = g.node_first[strip], n1 = g.node_first[strip + 1];
      const int width = bits_for_count(uint64_t{n1 - n0} + 1);
      for (uint32_t k = g.successor_first[g.arc_first[n0]]; k < g.successor_first[g.arc_first[n1]];
           ++k)
        bits.write(local(strip, g.successors[k]), width);
    }
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding SETS");
  }
}

Result<SetsSummary> read_sets_summary(const uint8_t* data, size_t size) {
  return parse_fixed(data, size);
}

Result<SetsGraph> decode_sets(const uint8_t* data, size_t size, SetsSummary* summary) {
  LODBAKE_ASSIGN_OR_RETURN(SetsSummary s, parse_fixed(data, size));
  if (summary != nullptr) *summary = s;
  try {
    SetsGraph g;
    LODBAKE_RETURN_IF_ERROR(decode_stream(data, size, s, &g));
    Status structure = check_sets_structure(g);
    if (!structure.is_ok()) return bad_sets(structure.message());
    return g;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding SETS");
  }
}

std::vector<uint32_t> strip_change_lods(const SetsGraph& g, size_t strip) {
  std::vector<uint32_t> lods{0};
  auto add = [&](uint32_t label) {
    if (label + 1 < g.lod_count) lods.push_back(label + 1);
  };
  for (uint32_t k = g.beginning_first[strip]; k < g.beginning_first[strip + 1]; ++k)
    add(g.beginning_lod[k]);
  for (uint32_t a = g.arc_first[g.node_first[strip]]; a < g.arc_first[g.node_first[strip + 1]]; ++a)
    add(g.arc_lod[a]);
  std::sort(lods.begin(), lods.end());
  lods.erase(std::unique(lods.begin(), lods.end()), lods.end());
  return lods;
}

Result<std::vector<uint32_t>> walk_strip(const SetsGraph& g, size_t strip, uint32_t lod) {
  if (lod >= g.lod_count)
    return invalid_input(string_printf("LoD %u out of range (%u LoDs)", lod, g.lod_count));
  const uint32_t n0 = g.node_first[strip];
  const uint32_t nodes = g.node_first[strip + 1] - n0;
  std::vector<uint32_t> cursor(nodes, kSetsEnd), end(nodes, 0);
  std::vector<uint32_t> sequence;
  uint32_t node = g.beginning_node[find_label(g.beginning_lod, g.beginning_first[strip],
                                              g.beginning_first[strip + 1], lod)];
  while (node != kSetsEnd) {
    sequence.push_back(g.node_vertex[node]);
    const uint32_t local = node - n0;
    if (cursor[local] == kSetsEnd) {
      const uint32_t arc = find_label(g.arc_lod, g.arc_first[node], g.arc_first[node + 1], lod);
      cursor[local] = g.successor_first[arc];
      end[local] = g.successor_first[arc + 1];
    }
    // Every step consumes one successor of a finite run, so the walk ends.
    if (cursor[local] == end[local])
      return invalid_input(string_printf(
          "strip %zu at LoD %u: node %u (vertex %u) is visited more often than its successor run "
          "has entries",
          strip, lod, local, g.node_vertex[node]));
    node = g.successors[cursor[local]++];
  }
  return sequence;
}

std::vector<std::string> validate_sets(const SetsGraph& g) {
  std::vector<std::string> findings;
  Status structure = check_sets_structure(g);
  if (!structure.is_ok()) {
    findings.push_back(structure.message());
    return findings;
  }
  uint64_t bad_walks = 0, longer = 0;
  std::string first_bad, first_longer;
  for (size_t s = 0; s < g.strip_count(); ++s) {
    size_t full_length = 0;
    for (uint32_t lod : strip_change_lods(g, s)) {
      Result<std::vector<uint32_t>> walked = walk_strip(g, s, lod);
      if (!walked.is_ok()) {
        if (bad_walks++ == 0) first_bad = walked.status().message();
        break;
      }
      if (lod == 0) {
        full_length = walked.value().size();
      } else if (walked.value().size() > full_length) {
        if (longer++ == 0)
          first_longer = string_printf("strip %zu has %zu indices at LoD %u, %zu at LoD 0", s,
                                       walked.value().size(), lod, full_length);
      }
    }
  }
  if (bad_walks != 0)
    findings.push_back(string_printf("%" PRIu64 " strips do not reach END, first: %s", bad_walks,
                                     first_bad.c_str()));
  if (longer != 0)
    findings.push_back(string_printf("%" PRIu64 " strip LoDs longer than LoD 0, first: %s", longer,
                                     first_longer.c_str()));
  return findings;
}

}  // namespace lodbake

namespace lodbake {

std::vector<std::string> validate_sets_payload(const uint8_t* data, size_t size, bool has_vspl,
                                               const VsplSummary* vspl) {
  Result<SetsGraph> graph = decode_sets(data, size);
  if (!graph.is_ok()) return {graph.status().message()};
  std::vector<std::string> findings;
  if (!has_vspl) findings.push_back("no VSPL section holds the progressive mesh the graph follows");
  if (vspl != nullptr) {
    if (graph.value().vertex_count != vspl->full_vertex_count())
      findings.push_back(string_printf("graph over %u vertices, BASE and VSPL make %" PRIu64,
                                       graph.value().vertex_count, vspl->full_vertex_count()));
    if (uint64_t{graph.value().lod_count} != uint64_t{vspl->split_count} + 1)
      findings.push_back(string_printf("%u LoDs, VSPL's %u splits make %" PRIu64,
                                       graph.value().lod_count, vspl->split_count,
                                       uint64_t{vspl->split_count} + 1));
  }
  for (std::string& finding : validate_sets(graph.value()))
    findings.push_back(std::move(finding));
  return findings;
}

}  // namespace lodbake
