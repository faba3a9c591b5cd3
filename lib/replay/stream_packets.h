// The wire format of truly selective view-dependent streaming (Kim, Lee and
// Kobbelt, "View-dependent mesh streaming with minimal latency", section
// 5.3 and Figure 3; packet size, section 7.2): the client's view request
// (uplink), the base mesh with the roots' refinement data, vsplit packets
// and the end of an answer (downlink). Byte layout: docs/replay.md, "Mode
// `stream`". Every message is
//
//   byte 0      magic and version: 0xB1 (high nibble 0xB = stream message,
//               low nibble = version 1)
//   byte 1      type (StreamMessageType)
//   bytes 2-5   payload length, uint32 little-endian
//   payload     as the type says, bit fields packed LSB first
//               (formats/support/bit_packing.h), the last byte zero-padded
//
// The decoders take one whole message, refuse anything else with
// kInvalidInput ("stream message: ..."; a newer version: kUnsupported),
// bound every count by the bits that remain before allocating, and accept
// exactly one encoding of each message (what decodes re-encodes to the same
// bytes), so they never crash or over-allocate on hostile input.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/sections/rfin.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/message_family.h"

namespace lodbake {

inline constexpr uint8_t kStreamMagicVersion = 0xB1;
inline constexpr size_t kStreamHeaderBytes = 6;
/// The largest payload a decoder takes (64 MiB); the server splits longer
/// answers into several vsplit messages.
inline constexpr uint32_t kMaxStreamPayloadBytes = 1u << 26;
static_assert(kStreamHeaderBytes == kMessageHeaderBytes);

enum class StreamMessageType : uint8_t {
  kView = 1,         ///< client -> server: the viewing parameters
  kBase = 2,         ///< server -> client: base mesh + roots' refinement data
  kVsplits = 3,      ///< server -> client: a batch of vsplit packets
  kEndOfAnswer = 4,  ///< server -> client: the answer to a view is complete
  /// client -> server, a connection's first message: the leaves of the
  /// client's partial hierarchy (none: a new session, answered by the base
  /// and scene messages; else the session resumes from them, no answer).
  kResume = 5,
  kScene = 6,  ///< server -> client, after the base: the model's bounding sphere
};
inline constexpr uint8_t kStreamLastMessageType = 6;
/// The stream messages' framing, for the shared header check and for a
/// transport that receives them (lib/replay/stream_transport.h).
inline constexpr MessageFamily kStreamMessages{"stream", kStreamMagicVersion,
                                               kStreamLastMessageType, kMaxStreamPayloadBytes};

/// The client's viewing parameters (the paper's Figure 3(a)).
struct ViewRequest {
  /// World to eye coordinates, column-major as OpenGL stores it (the eye
  /// looks down -z, up is +y). The last row must be (0, 0, 0, 1) and the
  /// upper 3x3 invertible; distances are measured in world units, so a
  /// rigid transform (gluLookAt) is what the criteria expect.
  std::array<float, 16> modelview{};
  float fovy_degrees = 60;  ///< vertical field of view, in (0, 180)
  float aspect = 4.0f / 3;  ///< width / height, > 0
  /// Screen-space tolerance as a fraction of the viewport height (pixels /
  /// height); 0 asks for every split (the whole hierarchy).
  float tolerance = 0;
  /// Near plane distance in world units (> 0); not in the paper's packet,
  /// which leaves the near plane implicit.
  float near_distance = 0.01f;
  bool operator==(const ViewRequest& o) const;
};
/// Payload bytes of a view request: 16 + 4 float32.
inline constexpr size_t kViewRequestPayloadBytes = 80;

/// The bits of a <tree-id, node-id>: ceil(log2 #roots) for the tree and the
/// hierarchy's depth for the heap id (hierarchy_shape()).
struct StreamIdWidths {
  int tree_bits = 0;  ///< bits_for_count(roots), 0..32
  int node_bits = 1;  ///< 1..64
  int id_bits() const { return tree_bits + node_bits; }
  /// An asset's stream (the base message says so): the wedge count of its
  /// WEDG (wedge ids take bits_for_count(wedges)) and the base mesh's
  /// triangle count (a base face id takes bits_for_count(base_faces)). 0:
  /// a position-only stream, whose packets carry no wedge data.
  uint32_t wedges = 0;
  uint32_t base_faces = 0;
  int wedge_bits() const;
  int base_face_bits() const;
};

/// A face of the client's mesh as the hierarchy names it: base triangle
/// `tree` when heap is 0, else the face that the split of node <tree,
/// heap> adds on `side` (0: the left wing, 1: the right wing).
struct WedgeFace {
  uint32_t tree = 0;
  uint64_t heap = 0;
  uint8_t side = 0;
  bool operator==(const WedgeFace& o) const {
    return tree == o.tree && heap == o.heap && side == o.side;
  }
  bool operator<(const WedgeFace& o) const {
    return tree != o.tree ? tree < o.tree : heap != o.heap ? heap < o.heap : side < o.side;
  }
};

/// A face whose corner the split moves to the removed (right) child, and
/// the wedge it takes there.
struct MovedWedge {
  WedgeFace face;
  uint32_t wedge = 0;
  bool operator==(const MovedWedge& o) const { return face == o.face && wedge == o.wedge; }
};

/// The wedge of a wing corner at every ancestor of the node w the
/// hierarchy's progressive mesh had the wing at (w is the fundamental cut
/// vertex `lift` levels up): the added face's wedge at w, replaced by
/// `changes[i].second` from `changes[i].first` levels above w on (levels
/// strictly increasing, each at most w's depth).
struct WingWedges {
  uint32_t lift = 0;
  std::vector<std::pair<uint32_t, uint32_t>> changes;
  bool operator==(const WingWedges& o) const { return lift == o.lift && changes == o.changes; }
};

/// The wedge data of one split (an asset's stream only): the corners of
/// the faces it adds (PmWedges::added order: (vs, vt, vl) then (vt, vs,
/// vr); a missing wing's three are kNoVertex), the moved faces' wedges at
/// the right child, and each present wing's wedges up the hierarchy.
struct VsplitWedges {
  std::array<uint32_t, 6> added{kNoVertex, kNoVertex, kNoVertex, kNoVertex, kNoVertex, kNoVertex};
  std::vector<MovedWedge> moved;
  std::array<WingWedges, 2> wings;
  bool operator==(const VsplitWedges& o) const {
    return added == o.added && moved == o.moved && wings == o.wings;
  }
};

/// One child's (or root's) refinement data: a leaf of the complete
/// hierarchy sends only its flag (qrefine() is never asked about it).
struct StreamNodeData {
  bool internal = false;
  RfinRecord record;  ///< zero for a leaf
  bool operator==(const StreamNodeData& o) const;
};

/// The paper's Figure 3(b). Topology: three <tree-id, node-id>, 3 x
/// id_bits() (the paper: 3 x 32 = 96 bits); a missing wing (boundary) is
/// heap id 0 with tree id 0.
struct VsplitPacket {
  HierarchyNodeId vs;
  HierarchyNodeId cut_left;
  HierarchyNodeId cut_right;
  /// The right (removed) child's position; the left child keeps vs's
  /// (half-edge collapses), so it is not sent.
  Vec3f position{};
  StreamNodeData left;
  StreamNodeData right;
  /// Sent only when the widths say the stream has wedges.
  VsplitWedges wedges;
  bool operator==(const VsplitPacket& o) const;
};

struct BaseMessage {
  /// Base mesh over the roots (vertex i = tree i), float32 positions.
  TriangleMesh mesh;
  /// The hierarchy's depth (node-id bits, 1..64).
  int node_bits = 1;
  /// One entry per root.
  std::vector<StreamNodeData> roots;
  /// An asset's stream: its WEDG's wedge count and the base triangles'
  /// corner wedges (one entry per triangle). 0 and empty: no wedges.
  uint32_t wedge_count = 0;
  std::vector<std::array<uint32_t, 3>> corners;
};

/// Bits of one packet's fields (without message framing): topology 3 x
/// id_bits, geometry 96, two leaf flags, 144 per internal child, and the
/// wedge data's bits when the widths have wedges (vsplit_wedge_bits()).
uint64_t vsplit_packet_bits(const VsplitPacket& packet, const StreamIdWidths& widths);
/// The bits of a packet's wedge data alone (0 without wedges).
uint64_t vsplit_wedge_bits(const VsplitPacket& packet, const StreamIdWidths& widths);
inline constexpr int kStreamPositionBits = 96;
inline constexpr int kStreamRecordBits = 144;

/// The type of a whole message after checking its header: magic, version
/// (newer: kUnsupported), a known type and a length that is the rest of the
/// bytes and at most kMaxStreamPayloadBytes.
Result<StreamMessageType> stream_message_type(const uint8_t* data, size_t size);

/// The payload length a message header announces, from its first
/// kStreamHeaderBytes alone (what a transport reads before the payload):
/// the same checks as stream_message_type() except that the payload is not
/// there yet, with the length bounded by `max_payload` (at most
/// kMaxStreamPayloadBytes), so a peer announcing a huge message is refused
/// before anything is allocated for it.
Result<uint32_t> stream_payload_length(const uint8_t* header, size_t size,
                                       uint32_t max_payload = kMaxStreamPayloadBytes);

Bytes encode_view_request(const ViewRequest& view);
/// Refuses non-finite values, a modelview whose last row is not (0, 0, 0, 1)
/// or whose 3x3 part is singular, fovy outside (0, 180), aspect <= 0, a
/// negative tolerance, near <= 0.
Result<ViewRequest> decode_view_request(const uint8_t* data, size_t size);

/// \return kInvalidInput when the mesh has no vertex or an index out of
///         range, a root entry is missing, or node_bits is outside 1..64.
Result<Bytes> encode_base_message(const BaseMessage& base);
/// Payload: uint32 roots, uint32 triangles, uint8 node_bits, uint8 flags
/// (1: wedges, else 0), two zero bytes, with wedges a uint32 wedge count,
/// roots x 3 float32, then bits: 3 x bits_for_count(roots) per triangle,
/// then per root a flag bit and (internal) its record, then with wedges 3 x
/// bits_for_count(wedge count) per triangle. Refuses a wedge out of range.
Result<BaseMessage> decode_base_message(const uint8_t* data, size_t size);

/// `root_count` bounds the tree ids (and gives tree_bits).
/// \return kInvalidInput for an id outside the widths or the roots.
Result<Bytes> encode_vsplit_message(const std::vector<VsplitPacket>& packets,
                                    const StreamIdWidths& widths, uint32_t root_count);
/// Payload: uint32 count, then the packets' bits; with wedges each packet
/// ends with its wedge data (layout in docs/replay.md). Refuses a heap id 0
/// for vs, a tree id >= root_count, a missing wing with a tree id, both
/// wings missing, non-finite positions, invalid records, a wedge or base
/// face out of range, a lift or change level above the hierarchy's depth,
/// a count that the remaining bits cannot hold, nonzero padding.
Result<std::vector<VsplitPacket>> decode_vsplit_message(const uint8_t* data, size_t size,
                                                        const StreamIdWidths& widths,
                                                        uint32_t root_count);

/// Payload: uint32, the number of vsplit packets of the whole answer.
Bytes encode_end_of_answer(uint32_t packets);
Result<uint32_t> decode_end_of_answer(const uint8_t* data, size_t size);

/// A new session's first message: a resume message without leaves (no id
/// widths needed: the client has not seen the base yet).
Bytes encode_hello();
/// The leaves of a client's partial hierarchy (ids of the complete one),
/// which the encoder sorts. \return kInvalidInput for an id outside the
/// widths or the roots, heap id 0, or a repeated id.
Result<Bytes> encode_resume_message(std::vector<HierarchyNodeId> leaves,
                                    const StreamIdWidths& widths, uint32_t root_count);
/// Payload: uint32 count, then count x (tree bits + node bits) in strictly
/// increasing <tree-id, node-id> order (one encoding). Refuses more than
/// `max_leaves` ids (the server passes its hierarchy's node count) before
/// allocating, heap id 0, a tree id >= root_count, ids out of order or
/// repeated, nonzero padding. Whether the ids form a front of the server's
/// hierarchy is the server's check (StreamServerSession::resume()).
Result<std::vector<HierarchyNodeId>> decode_resume_message(const uint8_t* data, size_t size,
                                                           const StreamIdWidths& widths,
                                                           uint32_t root_count,
                                                           uint64_t max_leaves);
/// The leaf count of a resume message from its first 10 bytes (0 for a
/// hello), for a server that has to tell a new session from a resumed one
/// before it knows which widths apply. kInvalidInput when not a resume message.
Result<uint32_t> resume_leaf_count(const uint8_t* data, size_t size);

/// Payload: the bounding sphere's centre (3 float32) and radius (float32,
/// > 0), all finite: what a client needs to place its camera path without
/// the container.
Bytes encode_scene_message(const BoundingSphere& sphere);
Result<BoundingSphere> decode_scene_message(const uint8_t* data, size_t size);

}  // namespace lodbake
