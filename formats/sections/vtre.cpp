// VTRE section codec: vertex trees of To, Lau & Green (Presence 2001,
// section 5.1: base, left and right node records), byte layout in
// docs/format.md "VTRE".
//
// Choices where the paper's records do not fit a file:
// - Records are stored in node order (base nodes, then each split's left and
//   right node), so the paper's VID is implied by the position and not
//   stored; a left record keeps its PID (the parent vertex), without which
//   the trees cannot be rebuilt.
// - Ids take bits(B + S) instead of 16 bits, and a fan is a list of runs
//   (closed bit + length each) instead of one closed bit and a 7-bit length,
//   so that any vertex degree and non-manifold vertices fit.
// - The paper's vertex state (equation (2)) is 0 or 1: one bit in base and
//   left records; a right record has its left sibling's, as in the paper.
// - Coordinates are float32 (the paper's are 2-byte values) in one block
//   before the bit stream, base vertices then left nodes: their size is
//   known from the fixed fields, which bounds B + S before allocation.
#include "formats/sections/vtre.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_vtre(const std::string& detail) {
  return malformed_section(kVtreTag, detail);
}

// Vertices that exist when node `node` appears: the base ones for a base
// node, B + k + 1 for split k's nodes.
uint64_t existing_at(uint64_t b, uint64_t node) {
  return node < b ? b : b + (node - b) / 2 + 1;
}

struct Widths {
  uint8_t id = 0;
  uint8_t run_count = 0;
  uint8_t run_length = 0;
};

Widths widths_of(const VertexTrees& t) {
  Widths w;
  w.id = static_cast<uint8_t>(bits_for_count(uint64_t{t.base_vertex_count} + t.split_count()));
  uint32_t max_runs = 0;
  uint32_t max_length = 0;
  for (size_t n = 0; n < t.node_count(); ++n)
    max_runs = std::max(max_runs, t.run_offsets[n + 1] - t.run_offsets[n]);
  for (size_t r = 0; r < t.run_count(); ++r)
    max_length = std::max(max_length, t.vertex_offsets[r + 1] - t.vertex_offsets[r]);
  w.run_count = static_cast<uint8_t>(bits_for_count(uint64_t{max_runs} + 1));
  w.run_length =
      t.run_count() == 0 ? 0 : static_cast<uint8_t>(bits_for_count(uint64_t{max_length} + 1));
  return w;
}

uint64_t fan_bits(const VertexTrees& t, size_t node, const Widths& w) {
  uint64_t bits = w.run_count;
  for (uint32_t r = t.run_offsets[node]; r < t.run_offsets[node + 1]; ++r)
    bits += 1 + w.run_length + uint64_t{w.id} * (t.vertex_offsets[r + 1] - t.vertex_offsets[r]);
  return bits;
}

Status parse_fixed(const uint8_t* data, size_t size, VtreSummary* s) {
  ByteReader reader(data, size);
  uint8_t reserved = 0;
  if (!reader.read(&s->base_vertex_count) || !reader.read(&s->split_count) ||
      !reader.read(&s->run_count) || !reader.read(&s->fan_vertex_count) ||
      !reader.read(&s->id_bits) || !reader.read(&s->run_count_bits) ||
      !reader.read(&s->run_length_bits) || !reader.read(&reserved)) {
    return bad_vtre(
        string_printf("payload has %zu bytes, the fixed fields need %zu", size, kVtreFixedBytes));
  }
  if (reserved != 0) return bad_vtre(string_printf("reserved byte is %u, must be 0", reserved));
  const uint64_t vertices = uint64_t{s->base_vertex_count} + s->split_count;
  if (vertices > UINT32_MAX - 1) {
    return bad_vtre(string_printf("%" PRIu64 " vertices, at most 2^32 - 2", vertices));
  }
  if (s->split_count != 0 && s->base_vertex_count == 0) {
    return bad_vtre(string_printf("%u splits without a base vertex", s->split_count));
  }
  if (s->id_bits != bits_for_count(vertices)) {
    return bad_vtre(string_printf("id bits %u, %" PRIu64 " vertices need %d", s->id_bits, vertices,
                                  bits_for_count(vertices)));
  }
  if (s->run_count_bits > 32) {
    return bad_vtre(string_printf("run count bits %u, at most 32", s->run_count_bits));
  }
  if (s->run_count == 0 ? s->run_length_bits != 0
                        : (s->run_length_bits < 2 || s->run_length_bits > 32 || s->id_bits == 0)) {
    return bad_vtre(string_printf("run length bits %u for %u runs of %" PRIu64
                                  " vertices (2..32, 0 without runs)",
                                  s->run_length_bits, s->run_count, vertices));
  }
  if (uint64_t{s->fan_vertex_count} < 2 * uint64_t{s->run_count} ||
      (s->run_count == 0 && s->fan_vertex_count != 0)) {
    return bad_vtre(string_printf("%u fan vertices cannot fill %u runs of at least 2",
                                  s->fan_vertex_count, s->run_count));
  }
  const uint64_t position_bytes = 12 * vertices;
  if (position_bytes > reader.remaining()) {
    return bad_vtre(string_printf("the coordinates of %" PRIu64 " vertices need %" PRIu64
                                  " bytes, only %zu remain",
                                  vertices, position_bytes, reader.remaining()));
  }
  // Lower bound of the record stream: every record's run count, every run's
  // closed bit and length, every fan entry.
  const uint64_t nodes = s->node_count();
  const uint64_t min_bits = nodes * s->run_count_bits +
                            uint64_t{s->run_count} * (1 + s->run_length_bits) +
                            uint64_t{s->fan_vertex_count} * s->id_bits;
  const uint64_t stream_bytes = reader.remaining() - position_bytes;
  if ((min_bits + 7) / 8 > stream_bytes) {
    return bad_vtre(
        string_printf("%" PRIu64 " nodes, %u runs and %u fan vertices need at least %" PRIu64
                      " bytes of records, %" PRIu64 " remain",
                      nodes, s->run_count, s->fan_vertex_count, (min_bits + 7) / 8, stream_bytes));
  }
  return Status::ok();
}

}  // namespace

std::vector<std::string> validate_vtre(const VertexTrees& t) {
  std::vector<std::string> findings;
  const uint64_t b = t.base_vertex_count;
  const uint64_t splits = t.split_count();
  const uint64_t vertices = b + splits;
  const uint64_t nodes = t.node_count();
  if (vertices > UINT32_MAX - 1) return {"more than 2^32 - 2 vertices"};
  if (splits != 0 && b == 0) return {"splits without a base vertex"};
  if (t.positions.size() != vertices || t.vertex_states.size() != vertices) {
    return {string_printf("%zu coordinates and %zu states for %" PRIu64 " vertices",
                          t.positions.size(), t.vertex_states.size(), vertices)};
  }
  if (t.run_offsets.size() != nodes + 1 || t.run_offsets[0] != 0 ||
      t.run_offsets.back() != t.run_count() || t.vertex_offsets.size() != t.run_count() + 1 ||
      t.vertex_offsets[0] != 0 || t.vertex_offsets.back() != t.fan_vertices.size() ||
      t.fan_vertices.size() > UINT32_MAX || t.run_count() > UINT32_MAX) {
    return {"fan offsets do not span the fan arrays"};
  }
  for (size_t n = 0; n < nodes; ++n) {
    if (t.run_offsets[n + 1] < t.run_offsets[n])
      return {string_printf("run offsets decrease at node %zu", n)};
  }
  for (size_t r = 0; r < t.run_count(); ++r) {
    if (t.vertex_offsets[r + 1] < t.vertex_offsets[r])
      return {string_printf("fan offsets decrease at run %zu", r)};
  }
  uint64_t bad_coordinates = 0, bad_states = 0, bad_parents = 0, bad_runs = 0, bad_fan = 0;
  std::string first_fan;
  for (const Vec3f& p : t.positions)
    bad_coordinates += !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]);
  for (uint8_t s : t.vertex_states)
    bad_states += s > 1;
  for (size_t k = 0; k < splits; ++k)
    bad_parents += t.parent_vertex[k] >= b + k;
  for (size_t n = 0; n < nodes; ++n) {
    const uint64_t existing = existing_at(b, n);
    const uint32_t own = t.node_vertex(n);
    for (uint32_t r = t.run_offsets[n]; r < t.run_offsets[n + 1]; ++r) {
      const uint32_t len = t.vertex_offsets[r + 1] - t.vertex_offsets[r];
      bad_runs += len < (t.run_closed[r] ? 3u : 2u) || t.run_closed[r] > 1;
      for (uint32_t k = t.vertex_offsets[r]; k < t.vertex_offsets[r + 1]; ++k) {
        const uint32_t v = t.fan_vertices[k];
        if (v >= existing || v == own) {
          if (bad_fan++ == 0) {
            first_fan =
                string_printf("node %zu (vertex %u) names vertex %u, %" PRIu64 " exist there", n,
                              own, v, existing);
          }
        }
      }
    }
  }
  if (bad_coordinates)
    findings.push_back(string_printf("%" PRIu64 " coordinates are not finite", bad_coordinates));
  if (bad_states)
    findings.push_back(string_printf("%" PRIu64 " vertex states are not 0 or 1", bad_states));
  if (bad_parents) {
    findings.push_back(string_printf(
        "%" PRIu64 " left nodes name a parent vertex that does not exist at their split",
        bad_parents));
  }
  if (bad_runs) {
    findings.push_back(string_printf(
        "%" PRIu64 " fan runs are too short (open: 2, closed: 3 vertices)", bad_runs));
  }
  if (bad_fan) {
    findings.push_back(string_printf("%" PRIu64
                                     " fan entries do not reference a valid node (first: %s)",
                                     bad_fan, first_fan.c_str()));
  }
  return findings;
}

VtreRecordSizes vtre_record_sizes(const VertexTrees& t) {
  VtreRecordSizes sizes;
  const Widths w = widths_of(t);
  for (size_t n = 0; n < t.node_count(); ++n) {
    const uint64_t fan = fan_bits(t, n, w);
    switch (t.kind(n)) {
      case VertexTreeNodeKind::kBase:
        ++sizes.base_records;
        sizes.base_bits += 96 + 1 + fan;
        break;
      case VertexTreeNodeKind::kLeft:
        ++sizes.left_records;
        sizes.left_bits += 96 + w.id + 1 + fan;
        break;
      case VertexTreeNodeKind::kRight:
        ++sizes.right_records;
        sizes.right_bits += fan;
        break;
    }
  }
  return sizes;
}

Result<Bytes> encode_vtre(const VertexTrees& t) {
  try {
    const std::vector<std::string> problems = validate_vtre(t);
    if (!problems.empty()) return invalid_input("cannot encode VTRE: " + problems.front());
    const Widths w = widths_of(t);
    Bytes out;
    ByteWriter writer(&out);
    writer.write(t.base_vertex_count);
    writer.write(static_cast<uint32_t>(t.split_count()));
    writer.write(static_cast<uint32_t>(t.run_count()));
    writer.write(static_cast<uint32_t>(t.fan_vertices.size()));
    writer.write(w.id);
    writer.write(w.run_count);
    writer.write(w.run_length);
    writer.write(uint8_t{0});
    for (const Vec3f& p : t.positions)
      for (float f : p)
        writer.write(f);
    BitWriter bits(&out);
    const uint32_t b = t.base_vertex_count;
    for (size_t n = 0; n < t.node_count(); ++n) {
      const VertexTreeNodeKind kind = t.kind(n);
      if (kind == VertexTreeNodeKind::kLeft) bits.write(t.parent_vertex[(n - b) / 2], w.id);
      if (kind == VertexTreeNodeKind::kBase) bits.write(t.vertex_states[n], 1);
      if (kind == VertexTreeNodeKind::kLeft) bits.write(t.vertex_states[b + (n - b) / 2], 1);
      bits.write(t.run_offsets[n + 1] - t.run_offsets[n], w.run_count);
      for (uint32_t r = t.run_offsets[n]; r < t.run_offsets[n + 1]; ++r) {
        bits.write(t.run_closed[r], 1);
        bits.write(t.vertex_offsets[r + 1] - t.vertex_offsets[r], w.run_length);
        for (uint32_t k = t.vertex_offsets[r]; k < t.vertex_offsets[r + 1]; ++k)
          bits.write(t.fan_vertices[k], w.id);
      }
    }
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding VTRE");
  }
}

Result<VtreSummary> read_vtre_summary(const uint8_t* data, size_t size) {
  VtreSummary s;
  LODBAKE_RETURN_IF_ERROR(parse_fixed(data, size, &s));
  return s;
}

Result<VertexTrees> decode_vtre(const uint8_t* data, size_t size, VtreSummary* summary,
                                VtreRecordSizes* sizes) {
  try {
    VtreSummary s;
    LODBAKE_RETURN_IF_ERROR(parse_fixed(data, size, &s));
    const uint32_t b = s.base_vertex_count;
    const uint64_t vertices = uint64_t{b} + s.split_count;
    const uint64_t nodes = s.node_count();
    VertexTrees t;
    t.base_vertex_count = b;
    // parse_fixed() checked that the coordinates and a lower bound of the
    // records fit in the payload, which bounds every allocation below.
    t.positions.resize(vertices);
    const uint8_t* p = data + kVtreFixedBytes;
    for (uint64_t v = 0; v < vertices; ++v) {
      for (int a = 0; a < 3; ++a) {
        std::memcpy(&t.positions[v][a], p, 4);
        p += 4;
        if (!std::isfinite(t.positions[v][a])) {
          return bad_vtre(string_printf("vertex %" PRIu64 " coordinate %d is not finite", v, a));
        }
      }
    }
    const size_t stream_size = size - static_cast<size_t>(p - data);
    BitReader in(p, stream_size);
    t.parent_vertex.resize(s.split_count);
    t.vertex_states.resize(vertices);
    t.run_offsets.reserve(nodes + 1);
    t.run_closed.reserve(s.run_count);
    t.vertex_offsets.reserve(uint64_t{s.run_count} + 1);
    t.fan_vertices.reserve(s.fan_vertex_count);
    VtreRecordSizes local;
    auto read = [&](int bits, uint32_t* out, const char* what, uint64_t node) -> Status {
      if (!in.read(bits, out)) {
        return bad_vtre(string_printf("records end inside the %s of node %" PRIu64, what, node));
      }
      return Status::ok();
    };
    for (uint64_t n = 0; n < nodes; ++n) {
      const VertexTreeNodeKind kind =
          n < b ? VertexTreeNodeKind::kBase
                : ((n - b) % 2 == 0 ? VertexTreeNodeKind::kLeft : VertexTreeNodeKind::kRight);
      const uint64_t start = in.bits_consumed();
      const uint64_t k = n < b ? 0 : (n - b) / 2;
      uint32_t value = 0;
      if (kind == VertexTreeNodeKind::kLeft) {
        LODBAKE_RETURN_IF_ERROR(read(s.id_bits, &value, "parent vertex", n));
        if (value >= b + k) {
          return bad_vtre(string_printf(
              "split %" PRIu64 ": parent vertex %u does not exist yet (%" PRIu64 " vertices)", k,
              value, b + k));
        }
        t.parent_vertex[k] = value;
      }
      if (kind != VertexTreeNodeKind::kRight) {
        LODBAKE_RETURN_IF_ERROR(read(1, &value, "vertex state", n));
        t.vertex_states[n < b ? n : b + k] = static_cast<uint8_t>(value);
      }
      const uint32_t own = kind == VertexTreeNodeKind::kBase
                               ? static_cast<uint32_t>(n)
                               : (kind == VertexTreeNodeKind::kLeft ? static_cast<uint32_t>(b + k)
                                                                    : t.parent_vertex[k]);
      const uint64_t existing = existing_at(b, n);
      uint32_t runs = 0;
      LODBAKE_RETURN_IF_ERROR(read(s.run_count_bits, &runs, "run count", n));
      if (uint64_t{runs} + t.run_closed.size() > s.run_count) {
        return bad_vtre(
            string_printf("node %" PRIu64 " has runs beyond the header's %u", n, s.run_count));
      }
      for (uint32_t r = 0; r < runs; ++r) {
        uint32_t closed = 0;
        uint32_t length = 0;
        LODBAKE_RETURN_IF_ERROR(read(1, &closed, "run closed bit", n));
        LODBAKE_RETURN_IF_ERROR(read(s.run_length_bits, &length, "run length", n));
        if (length < (closed ? 3u : 2u)) {
          return bad_vtre(string_printf("node %" PRIu64
                                        ": %s run of %u vertices (open: at least 2, closed: 3)",
                                        n, closed ? "closed" : "open", length));
        }
        if (uint64_t{length} + t.fan_vertices.size() > s.fan_vertex_count) {
          return bad_vtre(string_printf("node %" PRIu64 " has fan vertices beyond the header's %u",
                                        n, s.fan_vertex_count));
        }
        for (uint32_t j = 0; j < length; ++j) {
          LODBAKE_RETURN_IF_ERROR(read(s.id_bits, &value, "fan", n));
          if (value >= existing || value == own) {
            return bad_vtre(string_printf(
                "node %" PRIu64 " (vertex %u): fan vertex %u %s", n, own, value,
                value == own ? "is the node's own vertex" : "does not exist at that node"));
          }
          t.fan_vertices.push_back(value);
        }
        t.run_closed.push_back(static_cast<uint8_t>(closed));
        t.vertex_offsets.push_back(static_cast<uint32_t>(t.fan_vertices.size()));
      }
      t.run_offsets.push_back(static_cast<uint32_t>(t.run_closed.size()));
      const uint64_t bits = in.bits_consumed() - start;
      if (kind == VertexTreeNodeKind::kBase) {
        ++local.base_records;
        local.base_bits += 96 + bits;
      } else if (kind == VertexTreeNodeKind::kLeft) {
        ++local.left_records;
        local.left_bits += 96 + bits;
      } else {
        ++local.right_records;
        local.right_bits += bits;
      }
    }
    if (t.run_closed.size() != s.run_count || t.fan_vertices.size() != s.fan_vertex_count) {
      return bad_vtre(string_printf(
          "the records hold %zu runs and %zu fan vertices, the header says %u and %u",
          t.run_closed.size(), t.fan_vertices.size(), s.run_count, s.fan_vertex_count));
    }
    if (!in.padding_is_zero()) return bad_vtre("nonzero padding bits after the records");
    if (in.bytes_consumed() != stream_size) {
      return bad_vtre(
          string_printf("%zu trailing bytes after the records", stream_size - in.bytes_consumed()));
    }
    if (summary != nullptr) *summary = s;
    if (sizes != nullptr) *sizes = local;
    return t;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding VTRE");
  }
}

}  // namespace lodbake
