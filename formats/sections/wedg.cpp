#include "formats/sections/wedg.h"

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

Status bad(const std::string& detail) {
  return malformed_section(kWedgTag, detail);
}

std::string str(uint64_t v) {
  return std::to_string(v);
}

// The invariants both directions check; `what` prefixes the message.
std::string first_problem(const PmWedges& w) {
  const uint64_t count = w.wedge_primitive.size();
  if (w.wedge_vertex.size() != count || w.wedge_home.size() != count)
    return "the wedge table's lists differ in length";
  if (w.moved_offset.size() != w.added.size() + 1)
    return "the moved offsets are not one more than the splits";
  if (w.moved_offset.front() != 0 || w.moved_offset.back() != w.moved.size())
    return "the moved offsets do not cover the moved corners";
  for (size_t i = 1; i < w.moved_offset.size(); ++i)
    if (w.moved_offset[i] < w.moved_offset[i - 1]) return "the moved offsets decrease";
  for (const std::array<uint32_t, 3>& t : w.base)
    for (uint32_t v : t)
      if (v >= count) return "a base corner's wedge " + str(v) + " is out of range";
  for (size_t i = 0; i < w.added.size(); ++i)
    for (int face = 0; face < 2; ++face) {
      int missing = 0;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = w.added[i][face * 3 + k];
        if (v == kNoVertex) {
          ++missing;
        } else if (v >= count) {
          return "split " + str(i) + "'s added wedge " + str(v) + " is out of range";
        }
      }
      if (missing != 0 && missing != 3)
        return "split " + str(i) + " gives an added face some wedges and not others";
    }
  for (uint32_t v : w.moved)
    if (v >= count) return "a moved corner's wedge " + str(v) + " is out of range";
  return "";
}

}  // namespace

Result<Bytes> encode_wedg(const PmWedges& wedges) {
  if (wedges.moved_offset.empty())
    return invalid_input("cannot encode WEDG: the moved offsets are empty");
  if (std::string problem = first_problem(wedges); !problem.empty())
    return invalid_input("cannot encode WEDG: " + problem);
  Bytes out;
  ByteWriter w(&out);
  w.write<uint32_t>(0);  // flags
  w.write<uint32_t>(static_cast<uint32_t>(wedges.wedge_count()));
  w.write<uint32_t>(static_cast<uint32_t>(wedges.base.size()));
  w.write<uint32_t>(static_cast<uint32_t>(wedges.added.size()));
  w.write<uint32_t>(static_cast<uint32_t>(wedges.moved.size()));
  for (size_t i = 0; i < wedges.wedge_count(); ++i) {
    w.write<uint32_t>(wedges.wedge_primitive[i]);
    w.write<uint32_t>(wedges.wedge_vertex[i]);
    w.write<uint32_t>(wedges.wedge_home[i]);
  }
  for (const std::array<uint32_t, 3>& t : wedges.base)
    for (uint32_t v : t)
      w.write<uint32_t>(v);
  for (size_t i = 0; i < wedges.added.size(); ++i) {
    for (uint32_t v : wedges.added[i])
      w.write<uint32_t>(v);
    w.write<uint32_t>(wedges.moved_offset[i + 1] - wedges.moved_offset[i]);
  }
  for (uint32_t v : wedges.moved)
    w.write<uint32_t>(v);
  return out;
}

Result<PmWedges> decode_wedg(const uint8_t* data, size_t size) {
  ByteReader r(data, size);
  uint32_t flags = 0, wedges = 0, base = 0, splits = 0, moved = 0;
  if (!r.read(&flags) || !r.read(&wedges) || !r.read(&base) || !r.read(&splits) || !r.read(&moved))
    return bad("the header needs " + str(kWedgFixedBytes) + " bytes, " + str(size) + " remain");
  if (flags != 0) return bad("unknown flags " + str(flags));
  const uint64_t expected =
      kWedgFixedBytes + 12ull * wedges + 12ull * base + 28ull * splits + 4ull * moved;
  if (expected != size)
    return bad("the counts need " + str(expected) + " bytes, the payload has " + str(size));
  PmWedges out;
  out.wedge_primitive.resize(wedges);
  out.wedge_vertex.resize(wedges);
  out.wedge_home.resize(wedges);
  for (uint32_t i = 0; i < wedges; ++i) {
    r.read(&out.wedge_primitive[i]);
    r.read(&out.wedge_vertex[i]);
    r.read(&out.wedge_home[i]);
  }
  out.base.resize(base);
  for (std::array<uint32_t, 3>& t : out.base)
    for (uint32_t& v : t)
      r.read(&v);
  out.added.resize(splits);
  out.moved_offset.assign(1, 0);
  out.moved_offset.reserve(size_t{splits} + 1);
  uint64_t total = 0;
  for (uint32_t i = 0; i < splits; ++i) {
    for (uint32_t& v : out.added[i])
      r.read(&v);
    uint32_t count = 0;
    r.read(&count);
    total += count;
    if (total > moved)
      return bad("split " + str(i) + "'s moved corners pass the " + str(moved) + " stored");
    out.moved_offset.push_back(static_cast<uint32_t>(total));
  }
  if (total != moved)
    return bad("the splits move " + str(total) + " corners, " + str(moved) + " are stored");
  out.moved.resize(moved);
  for (uint32_t& v : out.moved)
    r.read(&v);
  if (std::string problem = first_problem(out); !problem.empty()) return bad(problem);
  return out;
}

std::vector<std::string> validate_wedg(const PmWedges& wedges, const ProgressiveMesh& pm) {
  std::vector<std::string> findings;
  for (uint32_t home : wedges.wedge_home)
    if (home >= pm.full_vertex_count()) {
      findings.push_back("a wedge's vertex " + str(home) + " is not one of VSPL's " +
                         str(pm.full_vertex_count()));
      break;
    }
  if (wedges.base.size() != pm.base.triangles.size())
    findings.push_back("WEDG names " + str(wedges.base.size()) + " base triangles, BASE has " +
                       str(pm.base.triangles.size()));
  if (wedges.added.size() != pm.splits.size()) {
    findings.push_back("WEDG describes " + str(wedges.added.size()) + " splits, VSPL has " +
                       str(pm.splits.size()));
    return findings;
  }
  for (size_t i = 0; i < pm.splits.size(); ++i) {
    const bool left = pm.splits[i].vl != kNoVertex, right = pm.splits[i].vr != kNoVertex;
    if (left != (wedges.added[i][0] != kNoVertex) || right != (wedges.added[i][3] != kNoVertex)) {
      findings.push_back("split " + str(i) + "'s added wedges do not match its wings");
      break;
    }
  }
  return findings;
}

std::vector<std::string> validate_wedg_corners(const PmWedges& w, const TriangleMesh& base) {
  auto one = [](std::string problem) { return std::vector<std::string>{std::move(problem)}; };
  if (!w.added.empty() || !w.moved.empty())
    return one("WEDG describes " + str(w.added.size()) +
               " splits but no VSPL section holds a progressive mesh");
  const size_t count = w.wedge_count();
  if (w.wedge_vertex.size() != count || w.wedge_home.size() != count)
    return one("WEDG's wedge table has lists of different lengths");
  if (w.base.size() != base.triangles.size())
    return one("WEDG names " + str(w.base.size()) + " triangles, BASE has " +
               str(base.triangles.size()));
  for (size_t t = 0; t < w.base.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t wedge = w.base[t][k];
      if (wedge >= count)
        return one("triangle " + str(t) + "'s wedge " + str(wedge) + " is out of range");
      if (w.wedge_home[wedge] != base.triangles[t][k])
        return one("triangle " + str(t) + "'s corner at vertex " + str(base.triangles[t][k]) +
                   " has wedge " + str(wedge) + " of vertex " + str(w.wedge_home[wedge]));
    }
    const uint32_t p = w.wedge_primitive[w.base[t][0]];
    if (w.wedge_primitive[w.base[t][1]] != p || w.wedge_primitive[w.base[t][2]] != p)
      return one("triangle " + str(t) + " has corners of two primitives");
  }
  return {};
}

}  // namespace lodbake
