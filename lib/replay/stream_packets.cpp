// Codec of the stream messages (lib/replay/stream_packets.h; Kim, Lee and
// Kobbelt 2005, Figure 3 and section 7.2). Choices where the paper is vague:
// - one magic/version byte, a type byte and a uint32 payload length frame
//   every message, so the same bytes can later travel over a socket;
// - ids are packed in their computed widths (tree: ceil(log2 #roots) bits,
//   heap id: the hierarchy's depth) instead of the paper's 32 bits each; a
//   missing wing is heap id 0 (no real node has it);
// - the geometry is the removed child's float32 position (VHIE stores
//   float32; the hierarchy has no quantized positions), the refinement data
//   RFIN's own record bits (float32 radius, mu^2, delta^2; 16-bit octahedral
//   axis and half-angle), so client and server evaluate qrefine() on the
//   same values; a leaf child sends only its flag;
// - an asset's wedge data ends each packet: wedge ids and base face ids in
//   their computed widths, counts and levels as Exp-Golomb codes (most are
//   0 or 1, and each code has one encoding);
// - floats travel as their IEEE-754 bits (so every message has one
//   encoding); NaN and infinities are refused everywhere, negative values
//   in refinement data, fov, aspect, tolerance and near where the header
//   says so.
#include "lib/replay/stream_packets.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <utility>

#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

Status bad(const std::string& detail) {
  return invalid_input("stream message: " + detail);
}

template <typename Sink>
void write_wide(Sink* w, uint64_t value, int bits) {
  if (bits <= 32) {
    w->write(static_cast<uint32_t>(value), bits);
  } else {
    w->write(static_cast<uint32_t>(value), 32);
    w->write(static_cast<uint32_t>(value >> 32), bits - 32);
  }
}

bool read_wide(BitReader* r, int bits, uint64_t* out) {
  uint32_t lo = 0, hi = 0;
  if (bits <= 32) {
    if (!r->read(bits, &lo)) return false;
    *out = lo;
    return true;
  }
  if (!r->read(32, &lo) || !r->read(bits - 32, &hi)) return false;
  *out = uint64_t{lo} | (uint64_t{hi} << 32);
  return true;
}

bool fits(uint64_t value, int bits) {
  return bits >= 64 || value < (uint64_t{1} << bits);
}

void write_record(BitWriter* w, const StreamNodeData& d) {
  w->write(d.internal ? 1 : 0, 1);
  if (!d.internal) return;
  w->write(float_bits(d.record.radius), 32);
  w->write(float_bits(d.record.mu2), 32);
  w->write(float_bits(d.record.delta2), 32);
  w->write(d.record.axis_x, 16);
  w->write(d.record.axis_y, 16);
  w->write(d.record.half_angle, 16);
}

// False when the bits run out; *bad_value when a float is not a valid RFIN value.
bool read_record(BitReader* r, StreamNodeData* d, bool* bad_value) {
  uint32_t flag = 0;
  if (!r->read(1, &flag)) return false;
  d->internal = flag != 0;
  d->record = RfinRecord();
  if (!d->internal) return true;
  uint32_t a = 0, b = 0, c = 0, x = 0, y = 0, h = 0;
  if (!r->read(32, &a) || !r->read(32, &b) || !r->read(32, &c) || !r->read(16, &x) ||
      !r->read(16, &y) || !r->read(16, &h)) {
    return false;
  }
  d->record.radius = bits_float(a);
  d->record.mu2 = bits_float(b);
  d->record.delta2 = bits_float(c);
  d->record.axis_x = static_cast<uint16_t>(x);
  d->record.axis_y = static_cast<uint16_t>(y);
  d->record.half_angle = static_cast<uint16_t>(h);
  if (!rfin_record_is_valid(d->record)) *bad_value = true;
  return true;
}

Bytes frame(StreamMessageType type, const Bytes& payload) {
  return frame_message(kStreamMessages, static_cast<uint8_t>(type), payload);
}

// The payload of a message of type `want`, after stream_message_type().
Result<ByteReader> open(const uint8_t* data, size_t size, StreamMessageType want,
                        const char* name) {
  return open_message(kStreamMessages, data, size, static_cast<uint8_t>(want), name);
}

uint64_t min_packet_bits(const StreamIdWidths& widths) {
  return 3 * static_cast<uint64_t>(widths.id_bits()) + kStreamPositionBits + 2;
}

bool valid_widths(const StreamIdWidths& widths, uint32_t root_count) {
  return root_count > 0 && widths.tree_bits == bits_for_count(root_count) &&
         widths.node_bits >= 1 && widths.node_bits <= 64;
}

// Exp-Golomb (order 0) of v < 2^32 - 1: bit_width(v + 1) - 1 zero bits,
// then v + 1 in bit_width(v + 1) bits, most significant first so that the
// leading 1 ends the zeros.
template <typename Sink>
void write_gamma(Sink* w, uint32_t v) {
  const uint64_t x = uint64_t{v} + 1;
  const int n = bit_width(x);
  for (int i = 0; i < n - 1; ++i)
    w->write(0, 1);
  for (int i = n - 1; i >= 0; --i)
    w->write(static_cast<uint32_t>((x >> i) & 1), 1);
}

bool read_gamma(BitReader* r, uint32_t* v) {
  int zeros = 0;
  uint32_t bit = 0;
  for (;;) {
    if (!r->read(1, &bit)) return false;
    if (bit != 0) break;
    if (++zeros > 31) return false;
  }
  uint64_t x = 1;
  for (int i = 0; i < zeros; ++i) {
    if (!r->read(1, &bit)) return false;
    x = x << 1 | bit;
  }
  if (x - 1 > 0xfffffffeu) return false;
  *v = static_cast<uint32_t>(x - 1);
  return true;
}

// Counts what a BitWriter would write.
struct BitCounter {
  uint64_t bits = 0;
  void write(uint32_t, int n) { bits += static_cast<uint64_t>(n); }
};

uint64_t remaining_bits(const BitReader& r, size_t size) {
  return uint64_t{size} * 8 - r.bits_consumed();
}

// A wedge that is usually one of `refs` (the split's own corners at the
// same vertex: one wedge there unless a seam passes): for each distinct
// reference in order a bit, 1 when it is that one, and after all of them
// 0 the wedge itself (never one of the references, so one encoding).
template <typename Sink>
void write_wedge_like(Sink* w, uint32_t wedge, std::array<uint32_t, 2> refs, int wb) {
  if (refs[1] == refs[0]) refs[1] = kNoVertex;
  for (uint32_t ref : refs) {
    if (ref == kNoVertex) continue;
    const bool hit = ref == wedge;
    w->write(hit ? 1 : 0, 1);
    if (hit) return;
  }
  w->write(wedge, wb);
}

bool read_wedge_like(BitReader* r, uint32_t* wedge, std::array<uint32_t, 2> refs,
                     const StreamIdWidths& widths) {
  if (refs[1] == refs[0]) refs[1] = kNoVertex;
  for (uint32_t ref : refs) {
    if (ref == kNoVertex) continue;
    uint32_t hit = 0;
    if (!r->read(1, &hit)) return false;
    if (hit != 0) {
      *wedge = ref;
      return true;
    }
  }
  return r->read(widths.wedge_bits(), wedge) && *wedge < widths.wedges && *wedge != refs[0] &&
         *wedge != refs[1];
}

// The wedge data of a packet; false when a value is out of range (the
// encoder's caller made it up). The vt corners and the moved faces' wedges
// refer to the split's vt wedges, the right face's vs corner to the left
// face's.
template <typename Sink>
bool write_wedges(Sink* w, const VsplitPacket& p, const StreamIdWidths& widths,
                  uint32_t root_count) {
  const VsplitWedges& d = p.wedges;
  const int wb = widths.wedge_bits();
  const HierarchyNodeId* cuts[2] = {&p.cut_left, &p.cut_right};
  const std::array<uint32_t, 6>& a = d.added;
  for (int side = 0; side < 2; ++side) {
    const bool present = cuts[side]->heap != 0;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = a[3 * side + k];
      if (present ? v >= widths.wedges : v != kNoVertex) return false;
    }
    const WingWedges& wing = d.wings[side];
    if (!present) {
      if (wing.lift != 0 || !wing.changes.empty()) return false;
      continue;
    }
    if (side == 0) {
      for (int k = 0; k < 3; ++k)
        w->write(a[k], wb);
    } else {
      write_wedge_like(w, a[3], {a[1], kNoVertex}, wb);
      write_wedge_like(w, a[4], {a[0], kNoVertex}, wb);
      w->write(a[5], wb);
    }
    const auto depth = static_cast<uint32_t>(bit_width(cuts[side]->heap) - 1);
    if (wing.lift > depth) return false;
    write_gamma(w, wing.lift);
    write_gamma(w, static_cast<uint32_t>(wing.changes.size()));
    uint32_t level = 0;
    for (const auto& [at, wedge] : wing.changes) {
      if (at <= level || at > depth - wing.lift || wedge >= widths.wedges) return false;
      write_gamma(w, at - level - 1);
      w->write(wedge, wb);
      level = at;
    }
  }
  write_gamma(w, static_cast<uint32_t>(d.moved.size()));
  for (const MovedWedge& m : d.moved) {
    if (m.wedge >= widths.wedges) return false;
    if (m.face.heap == 0) {
      if (m.face.tree >= widths.base_faces || m.face.side != 0) return false;
      w->write(0, 1);
      w->write(m.face.tree, widths.base_face_bits());
    } else {
      if (m.face.tree >= root_count || !fits(m.face.heap, widths.node_bits) || m.face.side > 1) {
        return false;
      }
      w->write(1, 1);
      w->write(m.face.tree, widths.tree_bits);
      write_wide(w, m.face.heap, widths.node_bits);
      w->write(m.face.side, 1);
    }
    write_wedge_like(w, m.wedge, {a[1], a[3]}, wb);
  }
  return true;
}

// "" or what is wrong with the packet's wedge data.
std::string read_wedges(BitReader* r, size_t size, VsplitPacket* p, const StreamIdWidths& widths,
                        uint32_t root_count) {
  VsplitWedges& d = p->wedges;
  const int wb = widths.wedge_bits();
  const HierarchyNodeId* cuts[2] = {&p->cut_left, &p->cut_right};
  auto wedge = [&](uint32_t* out) { return r->read(wb, out) && *out < widths.wedges; };
  std::array<uint32_t, 6>& a = d.added;
  for (int side = 0; side < 2; ++side) {
    if (cuts[side]->heap == 0) continue;
    const bool read = side == 0 ? wedge(&a[0]) && wedge(&a[1]) && wedge(&a[2])
                                : read_wedge_like(r, &a[3], {a[1], kNoVertex}, widths) &&
                                      read_wedge_like(r, &a[4], {a[0], kNoVertex}, widths) &&
                                      wedge(&a[5]);
    if (!read) return "a wedge is truncated or out of range";
    WingWedges& wing = d.wings[side];
    const auto depth = static_cast<uint32_t>(bit_width(cuts[side]->heap) - 1);
    uint32_t count = 0;
    if (!read_gamma(r, &wing.lift) || !read_gamma(r, &count)) return "truncated wedge data";
    if (wing.lift > depth) return "a wing lifted above its tree's root";
    if (count > depth - wing.lift) return "more wedge changes than levels";
    uint32_t level = 0;
    for (uint32_t i = 0; i < count; ++i) {
      uint32_t step = 0, v = 0;
      if (!read_gamma(r, &step)) return "truncated wedge data";
      if (step >= depth - wing.lift - level) return "a wedge change above its tree's root";
      level += step + 1;
      if (!wedge(&v)) return "a wedge is truncated or out of range";
      wing.changes.emplace_back(level, v);
    }
  }
  uint32_t moved = 0;
  if (!read_gamma(r, &moved)) return "truncated wedge data";
  // Each moved entry takes its kind bit, a face id and at least one bit.
  const uint64_t least =
      2 + static_cast<uint64_t>(std::min(widths.base_face_bits(), widths.id_bits() + 1));
  if (uint64_t{moved} * least > remaining_bits(*r, size)) {
    return std::to_string(moved) + " moved wedges need more bytes than remain";
  }
  d.moved.resize(moved);
  for (MovedWedge& m : d.moved) {
    uint32_t kind = 0, side = 0;
    if (!r->read(1, &kind)) return "truncated wedge data";
    if (kind == 0) {
      if (!r->read(widths.base_face_bits(), &m.face.tree)) return "truncated wedge data";
      if (m.face.tree >= widths.base_faces) return "a base face out of range";
    } else {
      if (!r->read(widths.tree_bits, &m.face.tree) ||
          !read_wide(r, widths.node_bits, &m.face.heap) || !r->read(1, &side)) {
        return "truncated wedge data";
      }
      if (m.face.tree >= root_count) return "tree id out of range";
      if (m.face.heap == 0) return "node id 0";
      m.face.side = static_cast<uint8_t>(side);
    }
    if (!read_wedge_like(r, &m.wedge, {a[1], a[3]}, widths))
      return "a wedge is truncated or out of range";
  }
  return "";
}

}  // namespace

bool ViewRequest::operator==(const ViewRequest& o) const {
  return std::memcmp(modelview.data(), o.modelview.data(), sizeof(float) * 16) == 0 &&
         float_bits(fovy_degrees) == float_bits(o.fovy_degrees) &&
         float_bits(aspect) == float_bits(o.aspect) &&
         float_bits(tolerance) == float_bits(o.tolerance) &&
         float_bits(near_distance) == float_bits(o.near_distance);
}

int StreamIdWidths::wedge_bits() const {
  return bits_for_count(wedges);
}

int StreamIdWidths::base_face_bits() const {
  return bits_for_count(base_faces);
}

bool StreamNodeData::operator==(const StreamNodeData& o) const {
  return internal == o.internal && float_bits(record.radius) == float_bits(o.record.radius) &&
         float_bits(record.mu2) == float_bits(o.record.mu2) &&
         float_bits(record.delta2) == float_bits(o.record.delta2) &&
         record.axis_x == o.record.axis_x && record.axis_y == o.record.axis_y &&
         record.half_angle == o.record.half_angle;
}

bool VsplitPacket::operator==(const VsplitPacket& o) const {
  return vs == o.vs && cut_left == o.cut_left && cut_right == o.cut_right &&
         float_bits(position[0]) == float_bits(o.position[0]) &&
         float_bits(position[1]) == float_bits(o.position[1]) &&
         float_bits(position[2]) == float_bits(o.position[2]) && left == o.left &&
         right == o.right && wedges == o.wedges;
}

uint64_t vsplit_wedge_bits(const VsplitPacket& p, const StreamIdWidths& widths) {
  if (widths.wedges == 0) return 0;
  BitCounter count;
  // A packet the encoder refuses has no size; count what it would write.
  (void)write_wedges(&count, p, widths, std::numeric_limits<uint32_t>::max());
  return count.bits;
}

uint64_t vsplit_packet_bits(const VsplitPacket& p, const StreamIdWidths& widths) {
  return min_packet_bits(widths) + (p.left.internal ? kStreamRecordBits : 0) +
         (p.right.internal ? kStreamRecordBits : 0) + vsplit_wedge_bits(p, widths);
}

Result<uint32_t> stream_payload_length(const uint8_t* header, size_t size, uint32_t max_payload) {
  return message_payload_length(kStreamMessages, header, size, max_payload);
}

Result<StreamMessageType> stream_message_type(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(uint8_t type, message_type(kStreamMessages, data, size));
  return static_cast<StreamMessageType>(type);
}

Bytes encode_view_request(const ViewRequest& view) {
  Bytes payload;
  ByteWriter w(&payload);
  for (float f : view.modelview)
    w.write(f);
  w.write(view.fovy_degrees);
  w.write(view.aspect);
  w.write(view.tolerance);
  w.write(view.near_distance);
  return frame(StreamMessageType::kView, payload);
}

Result<ViewRequest> decode_view_request(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kView, "view"));
  if (r.remaining() != kViewRequestPayloadBytes) {
    return bad("a view request has " + std::to_string(kViewRequestPayloadBytes) +
               " payload bytes, not " + std::to_string(r.remaining()));
  }
  ViewRequest v;
  for (float& f : v.modelview)
    r.read(&f);
  r.read(&v.fovy_degrees);
  r.read(&v.aspect);
  r.read(&v.tolerance);
  r.read(&v.near_distance);
  for (float f : v.modelview) {
    if (!std::isfinite(f)) return bad("a modelview entry is not finite");
  }
  const std::array<float, 16>& m = v.modelview;
  if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) {
    return bad("the modelview's last row is not (0, 0, 0, 1)");
  }
  const double det = double{m[0]} * (double{m[5]} * m[10] - double{m[9]} * m[6]) -
                     double{m[4]} * (double{m[1]} * m[10] - double{m[9]} * m[2]) +
                     double{m[8]} * (double{m[1]} * m[6] - double{m[5]} * m[2]);
  if (!(std::fabs(det) > 1e-12) || !std::isfinite(det)) return bad("the modelview is singular");
  if (!(v.fovy_degrees > 0 && v.fovy_degrees < 180)) return bad("fovy outside (0, 180)");
  if (!(v.aspect > 0) || !std::isfinite(v.aspect)) return bad("aspect is not positive");
  if (!(v.tolerance >= 0) || !std::isfinite(v.tolerance) || std::signbit(v.tolerance)) {
    return bad("tolerance is negative or not finite");
  }
  if (!(v.near_distance > 0) || !std::isfinite(v.near_distance)) {
    return bad("near distance is not positive");
  }
  return v;
}

Result<Bytes> encode_base_message(const BaseMessage& base) {
  const size_t roots = base.mesh.positions.size();
  if (roots == 0 || roots > 0xffffffffu) return invalid_input("base message: no roots");
  if (base.roots.size() != roots) {
    return invalid_input("base message: " + std::to_string(base.roots.size()) +
                         " root entries for " + std::to_string(roots) + " roots");
  }
  if (base.node_bits < 1 || base.node_bits > 64) {
    return invalid_input("base message: node bits outside 1..64");
  }
  const bool wedges = base.wedge_count != 0;
  if (wedges ? base.corners.size() != base.mesh.triangles.size() : !base.corners.empty()) {
    return invalid_input("base message: corner wedges without one entry per triangle");
  }
  try {
    Bytes payload;
    ByteWriter w(&payload);
    w.write(static_cast<uint32_t>(roots));
    w.write(static_cast<uint32_t>(base.mesh.triangles.size()));
    w.write(static_cast<uint8_t>(base.node_bits));
    w.write(static_cast<uint8_t>(wedges ? 1 : 0));
    w.write(uint16_t{0});
    if (wedges) w.write(base.wedge_count);
    for (const Vec3f& p : base.mesh.positions) {
      for (float c : p) {
        if (!std::isfinite(c)) return invalid_input("base message: a position is not finite");
        w.write(c);
      }
    }
    const int bits = bits_for_count(roots);
    BitWriter b(&payload);
    for (const Triangle& t : base.mesh.triangles) {
      for (uint32_t v : t) {
        if (v >= roots) return invalid_input("base message: a triangle index is out of range");
        b.write(v, bits);
      }
    }
    for (const StreamNodeData& d : base.roots)
      write_record(&b, d);
    const int wedge_bits = bits_for_count(base.wedge_count);
    for (const std::array<uint32_t, 3>& c : base.corners) {
      for (uint32_t v : c) {
        if (v >= base.wedge_count) return invalid_input("base message: a wedge is out of range");
        b.write(v, wedge_bits);
      }
    }
    b.finish();
    return frame(StreamMessageType::kBase, payload);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding the base message");
  }
}

Result<BaseMessage> decode_base_message(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kBase, "base mesh"));
  uint32_t roots = 0, triangles = 0;
  uint8_t node_bits = 0, pad8 = 0;
  uint16_t pad16 = 0;
  if (!r.read(&roots) || !r.read(&triangles) || !r.read(&node_bits) || !r.read(&pad8) ||
      !r.read(&pad16)) {
    return bad("base message shorter than its 12 fixed bytes");
  }
  if (pad8 > 1 || pad16 != 0) return bad("nonzero reserved bytes in the base message");
  uint32_t wedge_count = 0;
  if (pad8 == 1) {
    if (!r.read(&wedge_count)) return bad("base message without its wedge count");
    if (wedge_count == 0) return bad("a base message with wedges counts none");
  }
  if (roots == 0) return bad("base message without roots");
  if (node_bits < 1 || node_bits > 64) return bad("node bits outside 1..64");
  if (uint64_t{roots} * 12 > r.remaining()) {
    return bad(std::to_string(roots) + " roots need more bytes than remain");
  }
  const int bits = bits_for_count(roots);
  const uint64_t rest_bits = (uint64_t{r.remaining()} - uint64_t{roots} * 12) * 8;
  // Each triangle takes 3 x bits, each root at least its flag bit; a
  // one-root mesh (0-bit indices) cannot have a triangle of three vertices.
  const int wedge_bits = bits_for_count(wedge_count);
  if (uint64_t{triangles} * 3 * (bits + wedge_bits) + roots > rest_bits ||
      (bits == 0 && triangles != 0)) {
    return bad(std::to_string(triangles) + " triangles need more bytes than remain");
  }
  try {
    BaseMessage base;
    base.node_bits = node_bits;
    base.mesh.positions.resize(roots);
    for (Vec3f& p : base.mesh.positions) {
      for (float& c : p) {
        r.read(&c);
        if (!std::isfinite(c)) return bad("a base position is not finite");
      }
    }
    BitReader b(r.current(), r.remaining());
    base.mesh.triangles.resize(triangles);
    for (Triangle& t : base.mesh.triangles) {
      for (uint32_t& v : t) {
        b.read(bits, &v);
        if (v >= roots) return bad("a base triangle index is out of range");
      }
    }
    base.roots.resize(roots);
    for (StreamNodeData& d : base.roots) {
      bool bad_value = false;
      if (!read_record(&b, &d, &bad_value)) return bad("the roots' data is truncated");
      if (bad_value) return bad("a root's refinement data is negative or not finite");
    }
    base.wedge_count = wedge_count;
    if (wedge_count != 0) base.corners.resize(triangles);
    for (std::array<uint32_t, 3>& c : base.corners) {
      for (uint32_t& v : c) {
        if (!b.read(wedge_bits, &v)) return bad("the base corners' wedges are truncated");
        if (v >= wedge_count) return bad("a base corner's wedge is out of range");
      }
    }
    if (b.bytes_consumed() != r.remaining()) return bad("trailing bytes after the base message");
    if (!b.padding_is_zero()) return bad("nonzero padding bits in the base message");
    return base;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding the base message");
  }
}

Result<Bytes> encode_vsplit_message(const std::vector<VsplitPacket>& packets,
                                    const StreamIdWidths& widths, uint32_t root_count) {
  if (!valid_widths(widths, root_count)) return invalid_input("vsplit message: bad id widths");
  try {
    Bytes payload;
    ByteWriter w(&payload);
    w.write(static_cast<uint32_t>(packets.size()));
    BitWriter b(&payload);
    auto put_id = [&](const HierarchyNodeId& id, bool may_be_none) {
      if (id.heap == 0 ? (!may_be_none || id.tree != 0)
                       : (id.tree >= root_count || !fits(id.heap, widths.node_bits))) {
        return false;
      }
      b.write(id.tree, widths.tree_bits);
      write_wide(&b, id.heap, widths.node_bits);
      return true;
    };
    for (const VsplitPacket& p : packets) {
      if (p.vs.heap == 0 || !put_id(p.vs, false) || !put_id(p.cut_left, true) ||
          !put_id(p.cut_right, true) || (p.cut_left.heap == 0 && p.cut_right.heap == 0)) {
        return invalid_input("vsplit message: an id outside the hierarchy's widths");
      }
      for (float c : p.position) {
        if (!std::isfinite(c)) return invalid_input("vsplit message: a position is not finite");
        b.write(float_bits(c), 32);
      }
      write_record(&b, p.left);
      write_record(&b, p.right);
      if (widths.wedges != 0 && !write_wedges(&b, p, widths, root_count)) {
        return invalid_input("vsplit message: wedge data out of range or for a missing wing");
      }
    }
    b.finish();
    if (payload.size() > kMaxStreamPayloadBytes) {
      return invalid_input("vsplit message: payload over the limit");
    }
    return frame(StreamMessageType::kVsplits, payload);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding a vsplit message");
  }
}

Result<std::vector<VsplitPacket>> decode_vsplit_message(const uint8_t* data, size_t size,
                                                        const StreamIdWidths& widths,
                                                        uint32_t root_count) {
  if (!valid_widths(widths, root_count)) return invalid_input("vsplit message: bad id widths");
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kVsplits, "vsplit"));
  uint32_t count = 0;
  if (!r.read(&count)) return bad("vsplit message without its packet count");
  if (uint64_t{count} * min_packet_bits(widths) > uint64_t{r.remaining()} * 8) {
    return bad(std::to_string(count) + " vsplit packets need more bytes than remain");
  }
  try {
    std::vector<VsplitPacket> packets(count);
    BitReader b(r.current(), r.remaining());
    auto get_id = [&](HierarchyNodeId* id) {
      uint32_t tree = 0;
      uint64_t heap = 0;
      if (!b.read(widths.tree_bits, &tree) || !read_wide(&b, widths.node_bits, &heap)) {
        return false;
      }
      id->tree = tree;
      id->heap = heap;
      return true;
    };
    for (size_t i = 0; i < packets.size(); ++i) {
      VsplitPacket& p = packets[i];
      const std::string at = "vsplit packet " + std::to_string(i) + ": ";
      if (!get_id(&p.vs) || !get_id(&p.cut_left) || !get_id(&p.cut_right)) {
        return bad(at + "truncated");
      }
      if (p.vs.heap == 0) return bad(at + "node id 0");
      for (const HierarchyNodeId* id : {&p.vs, &p.cut_left, &p.cut_right}) {
        if (id->tree >= root_count) return bad(at + "tree id out of range");
        if (id->heap == 0 && id->tree != 0) return bad(at + "a missing wing with a tree id");
      }
      if (p.cut_left.heap == 0 && p.cut_right.heap == 0) return bad(at + "both wings missing");
      for (float& c : p.position) {
        uint32_t u = 0;
        if (!b.read(32, &u)) return bad(at + "truncated");
        c = bits_float(u);
        if (!std::isfinite(c)) return bad(at + "a position is not finite");
      }
      bool bad_value = false;
      if (!read_record(&b, &p.left, &bad_value) || !read_record(&b, &p.right, &bad_value)) {
        return bad(at + "truncated");
      }
      if (bad_value) return bad(at + "refinement data is negative or not finite");
      if (widths.wedges != 0) {
        const std::string wrong = read_wedges(&b, r.remaining(), &p, widths, root_count);
        if (!wrong.empty()) return bad(at + wrong);
      }
    }
    if (b.bytes_consumed() != r.remaining()) return bad("trailing bytes after the vsplit packets");
    if (!b.padding_is_zero()) return bad("nonzero padding bits in a vsplit message");
    return packets;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding a vsplit message");
  }
}

Bytes encode_end_of_answer(uint32_t packets) {
  Bytes payload;
  ByteWriter w(&payload);
  w.write(packets);
  return frame(StreamMessageType::kEndOfAnswer, payload);
}

Result<uint32_t> decode_end_of_answer(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r,
                           open(data, size, StreamMessageType::kEndOfAnswer, "end of answer"));
  uint32_t packets = 0;
  if (r.remaining() != 4 || !r.read(&packets)) return bad("end of answer is not 4 payload bytes");
  return packets;
}

Bytes encode_hello() {
  Bytes payload;
  ByteWriter w(&payload);
  w.write(uint32_t{0});
  return frame(StreamMessageType::kResume, payload);
}

Result<Bytes> encode_resume_message(std::vector<HierarchyNodeId> leaves,
                                    const StreamIdWidths& widths, uint32_t root_count) {
  if (!valid_widths(widths, root_count)) return invalid_input("resume message: bad id widths");
  try {
    std::sort(leaves.begin(), leaves.end());
    Bytes payload;
    ByteWriter w(&payload);
    w.write(static_cast<uint32_t>(leaves.size()));
    BitWriter b(&payload);
    for (size_t i = 0; i < leaves.size(); ++i) {
      const HierarchyNodeId& id = leaves[i];
      if (id.heap == 0 || id.tree >= root_count || !fits(id.heap, widths.node_bits) ||
          (i > 0 && leaves[i - 1] == id)) {
        return invalid_input("resume message: an id outside the hierarchy's widths or repeated");
      }
      b.write(id.tree, widths.tree_bits);
      write_wide(&b, id.heap, widths.node_bits);
    }
    b.finish();
    if (payload.size() > kMaxStreamPayloadBytes) {
      return invalid_input("resume message: payload over the limit");
    }
    return frame(StreamMessageType::kResume, payload);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding a resume message");
  }
}

Result<uint32_t> resume_leaf_count(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kResume, "resume"));
  uint32_t count = 0;
  if (!r.read(&count)) return bad("resume message without its leaf count");
  return count;
}

Result<std::vector<HierarchyNodeId>> decode_resume_message(const uint8_t* data, size_t size,
                                                           const StreamIdWidths& widths,
                                                           uint32_t root_count,
                                                           uint64_t max_leaves) {
  if (!valid_widths(widths, root_count)) return invalid_input("resume message: bad id widths");
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kResume, "resume"));
  uint32_t count = 0;
  if (!r.read(&count)) return bad("resume message without its leaf count");
  if (count > max_leaves) {
    return bad(std::to_string(count) + " leaves, more than the hierarchy's " +
               std::to_string(max_leaves) + " nodes");
  }
  if (uint64_t{count} * static_cast<uint64_t>(widths.id_bits()) > uint64_t{r.remaining()} * 8) {
    return bad(std::to_string(count) + " leaf ids need more bytes than remain");
  }
  try {
    std::vector<HierarchyNodeId> leaves(count);
    BitReader b(r.current(), r.remaining());
    for (size_t i = 0; i < leaves.size(); ++i) {
      uint32_t tree = 0;
      uint64_t heap = 0;
      if (!b.read(widths.tree_bits, &tree) || !read_wide(&b, widths.node_bits, &heap)) {
        return bad("resume message truncated");
      }
      leaves[i] = {tree, heap};
      const std::string at = "resume leaf " + std::to_string(i) + ": ";
      if (heap == 0) return bad(at + "node id 0");
      if (tree >= root_count) return bad(at + "tree id out of range");
      if (i > 0 && !(leaves[i - 1] < leaves[i])) return bad(at + "ids out of order or repeated");
    }
    if (b.bytes_consumed() != r.remaining()) return bad("trailing bytes after the resume leaves");
    if (!b.padding_is_zero()) return bad("nonzero padding bits in a resume message");
    return leaves;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding a resume message");
  }
}

Bytes encode_scene_message(const BoundingSphere& sphere) {
  return frame(StreamMessageType::kScene, sphere_payload(sphere));
}

Result<BoundingSphere> decode_scene_message(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, StreamMessageType::kScene, "scene"));
  return decode_sphere_payload(kStreamMessages, r);
}

}  // namespace lodbake
