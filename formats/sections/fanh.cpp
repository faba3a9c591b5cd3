// FANH section codec and validation (docs/format.md "FANH"). Choices:
// - node ids are bit-packed at the width of the node count, triangle ids at
//   the width of the triangle count, and every count (children per node,
//   list lengths) at one width stored in the header: the largest count's;
// - a child count is stored minus 2 (a fan-merge has a centre and at least
//   one collapsed child);
// - the totals in the fixed part fix the payload's exact size, so a decoder
//   checks the size before it allocates anything, and the modified total is
//   bounded by (collapsed children) x (triangles) so that zero-bit ids cannot
//   describe a huge list in a few bytes;
// - the deep check replays the merges over BASE with plain arrays; whether
//   each step leaves a manifold is lib/fanmerge's runtime check, not the
//   format's.
#include "formats/sections/fanh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

Status bad_fanh(const std::string& detail) {
  return malformed_section(kFanhTag, detail);
}

struct Widths {
  int node_bits;
  int triangle_bits;
  int count_bits;
};

uint64_t stream_bits(const FanhSummary& s, const Widths& w) {
  const uint64_t k = s.internal_count, c = s.child_entries;
  return k * w.count_bits + c * w.node_bits + 2 * (c - k) * w.count_bits +
         (uint64_t{s.removed_entries} + s.modified_entries) * w.triangle_bits;
}

// Bits of the largest count stored (children - 2, list lengths); at least 1.
// \pre the offsets are consistent.
int count_width(const FanHierarchy& h) {
  uint32_t largest = 0;
  for (size_t i = 0; i < h.internal_count(); ++i)
    largest = std::max(largest, h.child_start[i + 1] - h.child_start[i] - 2);
  for (size_t j = 0; j < h.children.size(); ++j)
    largest = std::max({largest, h.removed_start[j + 1] - h.removed_start[j],
                        h.modified_start[j + 1] - h.modified_start[j]});
  return std::max(1, bits_for_count(uint64_t{largest} + 1));
}

// One finding per kind of problem: its count and first instance.
class Findings {
 public:
  void add(const std::string& kind, const std::string& first) {
    for (Entry& e : entries_)
      if (e.kind == kind) {
        ++e.count;
        return;
      }
    entries_.push_back({kind, first, 1});
  }
  bool empty() const { return entries_.empty(); }
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    for (const Entry& e : entries_)
      out.push_back(std::to_string(e.count) + " " + e.kind + " (first: " + e.first + ")");
    return out;
  }

 private:
  struct Entry {
    std::string kind;
    std::string first;
    uint64_t count;
  };
  std::vector<Entry> entries_;
};

std::string node_name(const FanHierarchy& h, size_t i) {
  return "node " + std::to_string(uint64_t{h.vertex_count} + i);
}

}  // namespace

std::vector<std::string> validate_fanh_structure(const FanHierarchy& h) {
  const size_t k = h.internal_count();
  const size_t c = h.children.size();
  if (h.child_start.size() != k + 1 || h.child_start.front() != 0 || h.child_start.back() != c)
    return {"child offsets do not cover the " + std::to_string(c) + " children of " +
            std::to_string(k) + " nodes"};
  if (h.removed_start.size() != c + 1 || h.removed_start.front() != 0 ||
      h.removed_start.back() != h.removed.size() || h.modified_start.size() != c + 1 ||
      h.modified_start.front() != 0 || h.modified_start.back() != h.modified.size())
    return {"list offsets do not cover the removed and modified lists of " + std::to_string(c) +
            " children"};
  if (h.node_count() >= (uint64_t{1} << 32))
    return {std::to_string(h.node_count()) + " nodes, more than 2^32 - 1"};
  if (h.removed.size() >= (uint64_t{1} << 32) || h.modified.size() >= (uint64_t{1} << 32) ||
      c >= (uint64_t{1} << 32))
    return {"lists longer than 2^32 - 1 entries"};
  for (size_t j = 0; j < c; ++j)
    if (h.removed_start[j] > h.removed_start[j + 1] ||
        h.modified_start[j] > h.modified_start[j + 1])
      return {"list offsets decrease at child entry " + std::to_string(j)};
  // The counts V and T come from the file without bytes behind them, so
  // nothing here is sized by them: repeats are found by sorting copies of
  // the lists, whose lengths the payload bounds.
  Findings f;
  for (size_t i = 0; i < k; ++i) {
    const uint32_t b = h.child_start[i], e = h.child_start[i + 1];
    if (e < b || e - b < 2) {
      f.add("nodes with fewer than 2 children", node_name(h, i));
      if (e < b) return f.lines();
      continue;
    }
    const uint64_t id = uint64_t{h.vertex_count} + i;
    for (uint32_t j = b; j < e; ++j)
      if (h.children[j] >= id)
        f.add("children not made before their parent",
              node_name(h, i) + " has child " + std::to_string(h.children[j]));
    if (h.removed_start[b + 1] != h.removed_start[b] ||
        h.modified_start[b + 1] != h.modified_start[b])
      f.add("centre children with lists", node_name(h, i));
    if (!std::isfinite(h.error[i]) || h.error[i] < 0)
      f.add("non-finite or negative errors", node_name(h, i));
  }
  std::vector<uint32_t> sorted = h.children;
  std::sort(sorted.begin(), sorted.end());
  for (size_t j = 1; j < sorted.size(); ++j)
    if (sorted[j] == sorted[j - 1] && (j < 2 || sorted[j - 2] != sorted[j]))
      f.add("nodes that are a child twice", "node " + std::to_string(sorted[j]));
  for (uint32_t t : h.removed)
    if (t >= h.triangle_count)
      f.add("removed triangle ids out of range",
            std::to_string(t) + " of " + std::to_string(h.triangle_count));
  sorted = h.removed;
  std::sort(sorted.begin(), sorted.end());
  for (size_t j = 1; j < sorted.size(); ++j)
    if (sorted[j] == sorted[j - 1] && sorted[j] < h.triangle_count &&
        (j < 2 || sorted[j - 2] != sorted[j]))
      f.add("triangles removed twice", "triangle " + std::to_string(sorted[j]));
  for (uint32_t t : h.modified)
    if (t >= h.triangle_count)
      f.add("modified triangle ids out of range",
            std::to_string(t) + " of " + std::to_string(h.triangle_count));
  return f.lines();
}

std::vector<std::string> validate_fanh(const FanHierarchy& h, const TriangleMesh& base) {
  std::vector<std::string> findings = validate_fanh_structure(h);
  if (!findings.empty()) return findings;
  if (base.vertex_count() != h.vertex_count || base.triangle_count() != h.triangle_count)
    return {"hierarchy over " + std::to_string(h.vertex_count) + " vertices and " +
            std::to_string(h.triangle_count) + " triangles but BASE holds " +
            std::to_string(base.vertex_count()) + " and " + std::to_string(base.triangle_count())};
  for (const Triangle& t : base.triangles)
    for (uint32_t v : t)
      if (v >= h.vertex_count) return {"BASE has a vertex index out of range"};
  std::vector<Triangle> corners = base.triangles;
  std::vector<uint8_t> alive(corners.size(), 1);
  std::vector<uint32_t> degree(h.vertex_count, 0);
  for (const Triangle& t : corners)
    for (uint32_t v : t)
      ++degree[v];
  std::vector<uint32_t> vertex(h.node_count());
  for (uint32_t v = 0; v < h.vertex_count; ++v)
    vertex[v] = v;
  auto has = [](const Triangle& t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; };
  for (size_t i = 0; i < h.internal_count(); ++i) {
    const uint32_t b = h.child_start[i], e = h.child_start[i + 1];
    const uint32_t v = vertex[h.children[b]];
    vertex[h.vertex_count + i] = v;
    for (uint32_t j = b + 1; j < e; ++j) {
      const uint32_t c = vertex[h.children[j]];
      const std::string where = node_name(h, i) + " child " + std::to_string(j - b);
      const uint32_t rb = h.removed_start[j], re = h.removed_start[j + 1];
      const uint32_t mb = h.modified_start[j], me = h.modified_start[j + 1];
      for (uint32_t r = rb; r < re; ++r) {
        const uint32_t t = h.removed[r];
        if (!alive[t] || !has(corners[t], c) || !has(corners[t], v))
          return {where + ": removed triangle " + std::to_string(t) +
                  " is not an alive triangle of the child and the centre"};
      }
      for (uint32_t m = mb; m < me; ++m) {
        const uint32_t t = h.modified[m];
        if (!alive[t] || !has(corners[t], c) || has(corners[t], v))
          return {where + ": modified triangle " + std::to_string(t) +
                  " is not an alive triangle of the child without the centre"};
      }
      if (c == v || degree[c] != (re - rb) + (me - mb))
        return {where + ": its lists hold " + std::to_string((re - rb) + (me - mb)) +
                " triangles but vertex " + std::to_string(c) + " has " + std::to_string(degree[c])};
      for (uint32_t r = rb; r < re; ++r) {
        alive[h.removed[r]] = 0;
        for (uint32_t x : corners[h.removed[r]])
          --degree[x];
      }
      for (uint32_t m = mb; m < me; ++m)
        for (uint32_t& x : corners[h.modified[m]])
          if (x == c) x = v;
      degree[v] += me - mb;
      degree[c] -= me - mb;
    }
  }
  return {};
}

Result<Bytes> encode_fanh(const FanHierarchy& h) {
  std::vector<std::string> findings = validate_fanh_structure(h);
  if (!findings.empty()) return invalid_input("cannot encode FANH: " + findings.front());
  try {
    FanhSummary s;
    s.vertex_count = h.vertex_count;
    s.triangle_count = h.triangle_count;
    s.internal_count = static_cast<uint32_t>(h.internal_count());
    s.child_entries = static_cast<uint32_t>(h.children.size());
    s.removed_entries = static_cast<uint32_t>(h.removed.size());
    s.modified_entries = static_cast<uint32_t>(h.modified.size());
    Widths w{bits_for_count(h.node_count()), bits_for_count(h.triangle_count), count_width(h)};
    Bytes out;
    out.reserve(kFanhFixedBytes + 4 * h.internal_count() + stream_bits(s, w) / 8 + 1);
    ByteWriter bw(&out);
    bw.write(s.vertex_count);
    bw.write(s.triangle_count);
    bw.write(s.internal_count);
    bw.write(s.child_entries);
    bw.write(s.removed_entries);
    bw.write(s.modified_entries);
    bw.write(uint8_t{0});
    bw.write(static_cast<uint8_t>(w.node_bits));
    bw.write(static_cast<uint8_t>(w.triangle_bits));
    bw.write(static_cast<uint8_t>(w.count_bits));
    bw.write(uint32_t{0});
    for (float e : h.error)
      bw.write(e);
    BitWriter bits(&out);
    for (size_t i = 0; i < h.internal_count(); ++i) {
      const uint32_t b = h.child_start[i], e = h.child_start[i + 1];
      bits.write(e - b - 2, w.count_bits);
      for (uint32_t j = b; j < e; ++j)
        bits.write(h.children[j], w.node_bits);
      for (uint32_t j = b + 1; j < e; ++j) {
        bits.write(h.removed_start[j + 1] - h.removed_start[j], w.count_bits);
        bits.write(h.modified_start[j + 1] - h.modified_start[j], w.count_bits);
      }
    }
    for (uint32_t t : h.removed)
      bits.write(t, w.triangle_bits);
    for (uint32_t t : h.modified)
      bits.write(t, w.triangle_bits);
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding FANH");
  }
}

namespace {

Result<FanhSummary> read_fixed(const uint8_t* data, size_t size, Widths* w) {
  ByteReader r(data, size);
  FanhSummary s;
  uint8_t flags = 0, nb = 0, tb = 0, cb = 0;
  uint32_t reserved = 0;
  if (!r.read(&s.vertex_count) || !r.read(&s.triangle_count) || !r.read(&s.internal_count) ||
      !r.read(&s.child_entries) || !r.read(&s.removed_entries) || !r.read(&s.modified_entries) ||
      !r.read(&flags) || !r.read(&nb) || !r.read(&tb) || !r.read(&cb) || !r.read(&reserved))
    return bad_fanh("payload of " + std::to_string(size) + " bytes is shorter than the " +
                    std::to_string(kFanhFixedBytes) + "-byte fixed part");
  if (flags != 0) return bad_fanh("unknown flag bits " + std::to_string(flags));
  if (reserved != 0) return bad_fanh("reserved field is " + std::to_string(reserved) + ", not 0");
  const uint64_t nodes = uint64_t{s.vertex_count} + s.internal_count;
  if (nodes >= (uint64_t{1} << 32))
    return bad_fanh(std::to_string(nodes) + " nodes, more than 2^32 - 1");
  if (nb != bits_for_count(nodes) || tb != bits_for_count(s.triangle_count))
    return bad_fanh("index widths " + std::to_string(nb) + " and " + std::to_string(tb) +
                    " bits do not match " + std::to_string(nodes) + " nodes and " +
                    std::to_string(s.triangle_count) + " triangles");
  if (cb < 1 || cb > 32) return bad_fanh("count width " + std::to_string(cb) + " not in 1..32");
  if (uint64_t{s.child_entries} < 2 * uint64_t{s.internal_count})
    return bad_fanh(std::to_string(s.child_entries) + " children cannot give " +
                    std::to_string(s.internal_count) + " nodes 2 each");
  const uint64_t collapsed = uint64_t{s.child_entries} - s.internal_count;
  if (s.removed_entries > s.triangle_count ||
      s.modified_entries > collapsed * uint64_t{s.triangle_count})
    return bad_fanh("list totals " + std::to_string(s.removed_entries) + " and " +
                    std::to_string(s.modified_entries) + " exceed what " +
                    std::to_string(s.triangle_count) + " triangles allow");
  *w = {nb, tb, cb};
  const uint64_t expected =
      kFanhFixedBytes + 4 * uint64_t{s.internal_count} + (stream_bits(s, *w) + 7) / 8;
  if (expected != size)
    return bad_fanh("payload is " + std::to_string(size) + " bytes but its counts need " +
                    std::to_string(expected));
  return s;
}

}  // namespace

Result<FanhSummary> read_fanh_summary(const uint8_t* data, size_t size) {
  Widths w{};
  return read_fixed(data, size, &w);
}

Result<FanHierarchy> decode_fanh(const uint8_t* data, size_t size, FanhSummary* summary) {
  Widths w{};
  LODBAKE_ASSIGN_OR_RETURN(FanhSummary s, read_fixed(data, size, &w));
  try {
    FanHierarchy h;
    h.vertex_count = s.vertex_count;
    h.triangle_count = s.triangle_count;
    h.error.resize(s.internal_count);
    if (s.internal_count != 0)
      std::memcpy(h.error.data(), data + kFanhFixedBytes, 4 * size_t{s.internal_count});
    const size_t offset = kFanhFixedBytes + 4 * size_t{s.internal_count};
    BitReader bits(data + offset, size - offset);
    h.child_start.reserve(size_t{s.internal_count} + 1);
    h.children.reserve(s.child_entries);
    h.removed_start.reserve(size_t{s.child_entries} + 1);
    h.modified_start.reserve(size_t{s.child_entries} + 1);
    uint64_t removed = 0, modified = 0;
    for (uint32_t i = 0; i < s.internal_count; ++i) {
      uint32_t count = 0;
      // The size check guarantees the bits; a short read cannot happen, but
      // the sums below can still disagree with the totals.
      bits.read(w.count_bits, &count);
      const uint64_t children = uint64_t{count} + 2;
      if (h.children.size() + children > s.child_entries)
        return bad_fanh("node " + std::to_string(uint64_t{s.vertex_count} + i) +
                        "'s children run past the " + std::to_string(s.child_entries) +
                        " the header gives");
      for (uint64_t j = 0; j < children; ++j) {
        uint32_t id = 0;
        bits.read(w.node_bits, &id);
        h.children.push_back(id);
      }
      h.removed_start.push_back(static_cast<uint32_t>(removed));
      h.modified_start.push_back(static_cast<uint32_t>(modified));
      for (uint64_t j = 1; j < children; ++j) {
        uint32_t rc = 0, mc = 0;
        bits.read(w.count_bits, &rc);
        bits.read(w.count_bits, &mc);
        removed += rc;
        modified += mc;
        if (removed > s.removed_entries || modified > s.modified_entries)
          return bad_fanh("node " + std::to_string(uint64_t{s.vertex_count} + i) +
                          "'s lists run past the totals the header gives");
        h.removed_start.push_back(static_cast<uint32_t>(removed));
        h.modified_start.push_back(static_cast<uint32_t>(modified));
      }
      h.child_start.push_back(static_cast<uint32_t>(h.children.size()));
    }
    if (h.children.size() != s.child_entries || removed != s.removed_entries ||
        modified != s.modified_entries)
      return bad_fanh("the nodes hold " + std::to_string(h.children.size()) + " children, " +
                      std::to_string(removed) + " removed and " + std::to_string(modified) +
                      " modified entries, the header " + std::to_string(s.child_entries) + ", " +
                      std::to_string(s.removed_entries) + " and " +
                      std::to_string(s.modified_entries));
    h.removed.resize(s.removed_entries);
    for (uint32_t& t : h.removed)
      bits.read(w.triangle_bits, &t);
    h.modified.resize(s.modified_entries);
    for (uint32_t& t : h.modified)
      bits.read(w.triangle_bits, &t);
    if (!bits.padding_is_zero()) return bad_fanh("nonzero padding bits after the last list");
    // One encoding per hierarchy: the count width is the largest count's.
    if (w.count_bits != count_width(h))
      return bad_fanh("count width " + std::to_string(w.count_bits) +
                      " bits but the largest count needs " + std::to_string(count_width(h)));
    std::vector<std::string> findings = validate_fanh_structure(h);
    if (!findings.empty()) return bad_fanh(findings.front());
    if (summary != nullptr) *summary = s;
    return h;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding FANH");
  }
}

std::vector<std::string> validate_fanh_payload(const uint8_t* data, size_t size,
                                               const TriangleMesh& base) {
  Result<FanHierarchy> h = decode_fanh(data, size);
  if (!h.is_ok()) return {h.status().message()};
  return validate_fanh(h.value(), base);
}

FanhStats fanh_stats(const FanHierarchy& h) {
  FanhStats s;
  s.internal_nodes = h.internal_count();
  s.leaves = h.vertex_count;
  s.removed_entries = h.removed.size();
  s.modified_entries = h.modified.size();
  // Every node but a root is a child exactly once. Heights are kept for the
  // internal nodes only (a leaf's is 0; V has no bytes behind it), and
  // children have smaller ids than parents, so one pass in id order gives
  // them without recursion.
  s.roots = h.node_count() - h.children.size();
  std::vector<uint32_t> height(h.internal_count(), 0);
  for (size_t i = 0; i < h.internal_count(); ++i) {
    uint32_t best = 0;
    for (uint32_t j = h.child_start[i]; j < h.child_start[i + 1]; ++j) {
      const uint32_t child = h.children[j];
      const uint32_t below = child < h.vertex_count ? 0 : height[child - h.vertex_count];
      best = std::max(best, below + 1);
    }
    height[i] = best;
    s.depth = std::max<uint64_t>(s.depth, best);
  }
  if (s.internal_nodes != 0)
    s.average_children = static_cast<double>(h.children.size() - h.internal_count()) /
                         static_cast<double>(s.internal_nodes);
  return s;
}

}  // namespace lodbake
