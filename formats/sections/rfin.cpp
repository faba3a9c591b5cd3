// RFIN section codec: Hoppe's (1997, "View-dependent refinement of
// progressive meshes") per-vertex refinement data for the splits of a VHIE
// hierarchy; layout in docs/format.md "RFIN". Choices:
// - only internal nodes get a record: qrefine() is never asked about a
//   leaf (Kim, Lee and Kobbelt 5.3: a real leaf has no screen-space error);
// - radius, mu^2 and delta^2 stay float32 (they feed comparisons against a
//   tolerance; a coarse float would move the refinement front);
// - the cone axis is octahedral-mapped to 2 x 16 bits and the half-angle
//   stored in units of pi / 65535, rounded up after adding the axis's own
//   quantization error, so the stored cone always contains the true one and
//   the back-face test stays conservative.
#include "formats/sections/rfin.h"

#include <cmath>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngleUnit = kPi / 65535.0;

Status bad_rfin(const std::string& detail) {
  return malformed_section(kRfinTag, detail);
}

double sign_not_zero(double v) {
  return v < 0 ? -1.0 : 1.0;
}

void octa_encode(const Vec3f& a, uint32_t* qx, uint32_t* qy) {
  double x = a[0], y = a[1], z = a[2];
  const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
  if (!(l1 > 0)) {
    x = 0, y = 0, z = 1;
  } else {
    x /= l1, y /= l1, z /= l1;
  }
  double u = x, v = y;
  if (z < 0) {
    u = (1 - std::fabs(y)) * sign_not_zero(x);
    v = (1 - std::fabs(x)) * sign_not_zero(y);
  }
  auto q = [](double c) {
    const double t = std::round((c * 0.5 + 0.5) * 65535.0);
    return static_cast<uint32_t>(std::min(65535.0, std::max(0.0, t)));
  };
  *qx = q(u);
  *qy = q(v);
}

Vec3f octa_decode(uint32_t qx, uint32_t qy) {
  double u = qx / 65535.0 * 2 - 1;
  double v = qy / 65535.0 * 2 - 1;
  double z = 1 - std::fabs(u) - std::fabs(v);
  if (z < 0) {
    const double ou = u;
    u = (1 - std::fabs(v)) * sign_not_zero(ou);
    v = (1 - std::fabs(ou)) * sign_not_zero(v);
  }
  const double len = std::sqrt(u * u + v * v + z * z);
  return {static_cast<float>(u / len), static_cast<float>(v / len), static_cast<float>(z / len)};
}

double angle_between(const Vec3f& a, const Vec3f& b) {
  const double la = std::sqrt(double{a[0]} * a[0] + double{a[1]} * a[1] + double{a[2]} * a[2]);
  const double lb = std::sqrt(double{b[0]} * b[0] + double{b[1]} * b[1] + double{b[2]} * b[2]);
  if (!(la > 0) || !(lb > 0)) return kPi;
  // atan2 keeps small angles exact where acos of a rounded cosine does not.
  const double cx = double{a[1]} * b[2] - double{a[2]} * b[1];
  const double cy = double{a[2]} * b[0] - double{a[0]} * b[2];
  const double cz = double{a[0]} * b[1] - double{a[1]} * b[0];
  const double d = double{a[0]} * b[0] + double{a[1]} * b[1] + double{a[2]} * b[2];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d);
}

bool good(float v) {
  return std::isfinite(v) && v >= 0;
}

size_t split_count(const VertexHierarchy& h) {
  size_t n = 0;
  for (uint32_t c : h.first_child)
    n += c != kNoNode ? 1 : 0;
  return n;
}

}  // namespace

bool rfin_record_is_valid(const RfinRecord& record) {
  return good(record.radius) && good(record.mu2) && good(record.delta2);
}

Result<RfinRecord> quantize_refinement(const NodeRefinement& d) {
  if (!good(d.radius) || !good(d.mu2) || !good(d.delta2) || !good(d.cone_half_angle) ||
      !std::isfinite(d.cone_axis[0]) || !std::isfinite(d.cone_axis[1]) ||
      !std::isfinite(d.cone_axis[2])) {
    return invalid_input("a negative or non-finite value");
  }
  RfinRecord r;
  r.radius = d.radius;
  r.mu2 = d.mu2;
  r.delta2 = d.delta2;
  uint32_t qx = 0, qy = 0;
  octa_encode(d.cone_axis, &qx, &qy);
  const double err = angle_between(octa_decode(qx, qy), d.cone_axis);
  const double angle = std::min(kPi, double{d.cone_half_angle} + err);
  r.axis_x = static_cast<uint16_t>(qx);
  r.axis_y = static_cast<uint16_t>(qy);
  r.half_angle = static_cast<uint16_t>(std::min(65535.0, std::ceil(angle / kAngleUnit)));
  return r;
}

NodeRefinement dequantize_refinement(const RfinRecord& record) {
  NodeRefinement d;
  d.radius = record.radius;
  d.mu2 = record.mu2;
  d.delta2 = record.delta2;
  d.cone_axis = octa_decode(record.axis_x, record.axis_y);
  d.cone_half_angle = static_cast<float>(record.half_angle * kAngleUnit);
  return d;
}

Result<Bytes> encode_rfin(const VertexHierarchy& h, const std::vector<NodeRefinement>& data) {
  if (data.size() != h.node_count()) {
    return invalid_input("cannot encode RFIN: " + std::to_string(data.size()) + " records for " +
                         std::to_string(h.node_count()) + " nodes");
  }
  try {
    std::vector<RfinRecord> records;
    for (size_t i = 0; i < data.size(); ++i) {
      if (h.first_child[i] == kNoNode) continue;
      Result<RfinRecord> q = quantize_refinement(data[i]);
      if (!q.is_ok()) {
        return invalid_input("cannot encode RFIN: node " + std::to_string(i) +
                             " has a negative or non-finite value");
      }
      records.push_back(q.value());
    }
    Bytes out;
    ByteWriter w(&out);
    w.write(static_cast<uint32_t>(records.size()));
    w.write(uint32_t{0});
    for (const RfinRecord& r : records) {
      w.write(r.radius);
      w.write(r.mu2);
      w.write(r.delta2);
    }
    BitWriter bits(&out);
    for (const RfinRecord& r : records) {
      bits.write(r.axis_x, 16);
      bits.write(r.axis_y, 16);
      bits.write(r.half_angle, 16);
    }
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding RFIN");
  }
}

Result<uint32_t> read_rfin_summary(const uint8_t* data, size_t size) {
  ByteReader r(data, size);
  uint32_t splits = 0, flags = 0;
  if (!r.read(&splits) || !r.read(&flags)) {
    return bad_rfin("payload of " + std::to_string(size) +
                    " bytes is shorter than the 8-byte header");
  }
  if (flags != 0) return bad_rfin("unknown flags " + std::to_string(flags));
  const uint64_t need = kRfinFixedBytes + uint64_t{splits} * kRfinRecordBytes;
  if (need != size) {
    return bad_rfin("payload has " + std::to_string(size) + " bytes, " + std::to_string(splits) +
                    " records need " + std::to_string(need));
  }
  return splits;
}

Result<std::vector<RfinRecord>> decode_rfin_records(const uint8_t* data, size_t size,
                                                    const VertexHierarchy& h) {
  LODBAKE_ASSIGN_OR_RETURN(uint32_t splits, read_rfin_summary(data, size));
  if (splits != split_count(h)) {
    return bad_rfin(std::to_string(splits) + " records, VHIE has " +
                    std::to_string(split_count(h)) + " splits");
  }
  try {
    std::vector<RfinRecord> out(h.node_count());
    ByteReader r(data + kRfinFixedBytes, size - kRfinFixedBytes);
    for (size_t i = 0; i < out.size(); ++i) {
      if (h.first_child[i] == kNoNode) continue;
      RfinRecord& d = out[i];
      r.read(&d.radius);
      r.read(&d.mu2);
      r.read(&d.delta2);
      if (!rfin_record_is_valid(d)) {
        return bad_rfin("node " + std::to_string(i) + ": negative or non-finite value");
      }
    }
    BitReader bits(r.current(), r.remaining());
    for (size_t i = 0; i < out.size(); ++i) {
      if (h.first_child[i] == kNoNode) continue;
      uint32_t qx = 0, qy = 0, qa = 0;
      bits.read(16, &qx);
      bits.read(16, &qy);
      bits.read(16, &qa);
      out[i].axis_x = static_cast<uint16_t>(qx);
      out[i].axis_y = static_cast<uint16_t>(qy);
      out[i].half_angle = static_cast<uint16_t>(qa);
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding RFIN");
  }
}

Result<std::vector<NodeRefinement>> decode_rfin(const uint8_t* data, size_t size,
                                                const VertexHierarchy& h) {
  LODBAKE_ASSIGN_OR_RETURN(std::vector<RfinRecord> records, decode_rfin_records(data, size, h));
  try {
    std::vector<NodeRefinement> out(h.node_count());
    for (size_t i = 0; i < out.size(); ++i) {
      if (h.first_child[i] != kNoNode) out[i] = dequantize_refinement(records[i]);
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding RFIN");
  }
}

}  // namespace lodbake
