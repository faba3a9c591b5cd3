// The wire format of vertex-tree transmission (To, Lau & Green, "An adaptive
// multiresolution method for progressive model transmission", section 5.1):
// the paper's base, left and right node records, bit-packed, and the frame
// messages that carry them with the visible vertex list's moves. Byte
// layout and choices: docs/replay.md, "Mode `vtrees`". Every message is
//
//   byte 0      magic and version: 0xC1 (high nibble 0xC = vertex-tree
//               message, low nibble = version 1)
//   byte 1      type (VtreesMessageType)
//   bytes 2-5   payload length, uint32 little-endian
//   payload     fixed fields, then bit fields packed LSB first
//               (formats/support/bit_packing.h), the last byte zero-padded
//
// The client's view travels uplink as mode stream's view request
// (lib/replay/stream_packets.h), unchanged.
//
// The decoders take one whole message, refuse anything else with
// kInvalidInput ("vtrees message: ..."; a newer version: kUnsupported),
// bound every count by the bits that remain before allocating, and accept
// exactly one encoding of each message (what decodes re-encodes to the same
// bytes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/message_family.h"

namespace lodbake {

inline constexpr uint8_t kVtreesMagicVersion = 0xC1;
inline constexpr size_t kVtreesHeaderBytes = 6;
/// The largest payload a decoder takes (16 MiB).
inline constexpr uint32_t kMaxVtreesPayloadBytes = 1u << 24;
/// The most items one frame message holds; the server splits longer frames.
inline constexpr uint32_t kMaxVtreesItems = 1u << 16;

static_assert(kVtreesHeaderBytes == kMessageHeaderBytes);

enum class VtreesMessageType : uint8_t {
  kTrees = 1,  ///< server -> client, first: the widths and the base records
  kFrame = 2,  ///< server -> client: items (records, list moves, trace updates)
  /// Over a connection (VtreesClientSession), server -> client after the
  /// trees message: the model's bounding sphere, to place a camera path.
  kScene = 3,
  /// Over a connection, server -> client: the answer to a view is complete.
  kEndOfAnswer = 4,
};
inline constexpr uint8_t kVtreesLastMessageType = 4;
/// The vtrees messages' framing, for the shared header check and for a
/// transport that receives them (lib/replay/stream_transport.h).
inline constexpr MessageFamily kVtreesMessages{"vtrees", kVtreesMagicVersion,
                                               kVtreesLastMessageType, kMaxVtreesPayloadBytes};

/// What every record's field widths follow from, sent once in kTrees.
struct VtreesWidths {
  uint32_t base_count = 0;   ///< B: base vertices (>= 1)
  uint32_t split_count = 0;  ///< S: splits; vertex ids are < B + S
  int run_count_bits = 0;    ///< bits of a record's run count, 0..32
  int run_length_bits = 0;   ///< bits of a run's length, 0..32
  /// An asset's trees (wedge data in every record): the progressive mesh's
  /// face slots and WEDG's wedges, both >= 1; 0 and 0 for a mesh's trees.
  uint32_t slot_count = 0;
  uint32_t wedge_count = 0;
  /// bits_for_count(B + S): the paper's 16-bit VID and PID.
  int id_bits() const;
  /// bits_for_count(S): a list move's split id.
  int split_bits() const;
  bool has_wedges() const { return wedge_count != 0; }
  int slot_bits() const;   ///< bits_for_count(slot_count)
  int wedge_bits() const;  ///< bits_for_count(wedge_count)
  bool operator==(const VtreesWidths& o) const;
};

/// The widths of `trees` (the largest run count and run length over all
/// nodes). \pre the trees are validate_vtre() clean.
VtreesWidths vtrees_widths(const VertexTrees& trees);

/// A fan vertex the client does not hold yet (below its visible vertex
/// list) and for which it holds no first transmitted parent: `index` counts
/// entries over the record's runs in order.
struct VtreesTrace {
  uint32_t index = 0;
  uint32_t parent = 0;  ///< the vertex's first transmitted parent
  bool operator==(const VtreesTrace& o) const { return index == o.index && parent == o.parent; }
};

/// The face a fan pair stands for and that face's wedge at the node's
/// vertex (an asset's trees only).
struct VtreesPairWedge {
  uint32_t slot = 0;   ///< the progressive mesh's face slot
  uint32_t wedge = 0;  ///< the wedge of that slot's corner at the node's vertex
  bool operator==(const VtreesPairWedge& o) const { return slot == o.slot && wedge == o.wedge; }
};

/// The number of fan pairs (triangles) of a record's runs: length - 1 per
/// open run, length per closed one, in the client's order (each run's
/// consecutive pairs, then a closed run's last-to-first pair).
size_t vtrees_pair_count(const std::vector<uint32_t>& run_info);

/// One node record. Base: vid, position, state, fan. Left: vid (B + k for
/// split k), pid (the parent vertex vs), position, state, fan, traces.
/// Right: vid (= its left sibling's pid), fan, traces. An asset's records
/// also carry `pairs` (one per fan pair, vtrees_pair_count()).
struct VtreesNodeRecord {
  uint32_t vid = 0;
  uint32_t pid = 0;
  Vec3f position{};
  uint8_t state = 0;  ///< the paper's equation (2): 0 or 1
  /// Runs: run_info[r] = length << 1 | closed; their vertices in `fan`.
  std::vector<uint32_t> run_info;
  std::vector<uint32_t> fan;
  std::vector<VtreesTrace> traces;
  std::vector<VtreesPairWedge> pairs;
  bool operator==(const VtreesNodeRecord& o) const;
};

/// A wing face a split adds (an asset's trees only): its face slot, the
/// wedge of its wing corner at creation, and that corner's wedge carried
/// up the collapses where a front has it coarser than the progressive mesh
/// ever did: `changes` (vertex y, wedge), y strictly decreasing, each
/// below the split vertex; at an ancestor vertex x of the wing vertex the
/// wedge is that of the change with the smallest y >= x, else `wedge`.
struct VtreesWing {
  bool present = false;
  uint32_t slot = 0;
  uint32_t wedge = 0;
  std::vector<std::pair<uint32_t, uint32_t>> changes;
  bool operator==(const VtreesWing& o) const {
    return present == o.present && slot == o.slot && wedge == o.wedge && changes == o.changes;
  }
};

/// Node `node`'s record as stored in `trees`, without traces.
/// \pre node < trees.node_count().
VtreesNodeRecord vtrees_node_record(const VertexTrees& trees, uint32_t node);

/// Bits of one record of `kind` in the stream (fields only, no item tag).
uint64_t vtrees_record_bits(const VtreesNodeRecord& record, VertexTreeNodeKind kind,
                            const VtreesWidths& widths);
/// The trace-up part of a left or right record's bits.
uint64_t vtrees_trace_bits(const VtreesNodeRecord& record, const VtreesWidths& widths);
/// The wedge part of a record's bits (its pairs; 0 for a mesh's trees).
uint64_t vtrees_pair_bits(const VtreesNodeRecord& record, const VtreesWidths& widths);
/// Bits of a split item's two wings (0 for a mesh's trees).
uint64_t vtrees_wing_bits(const VtreesWing (&wings)[2], const VtreesWidths& widths);

enum class VtreesItemKind : uint8_t {
  kSplit = 0,        ///< split k's left and right records: the list moves down at new nodes
  kDown = 1,         ///< the list moves down at split k, whose records the client holds
  kUp = 2,           ///< the list moves up: split k's children are replaced by their parent
  kTraceUpdate = 3,  ///< a held first transmitted parent is superseded by a nearer one
};
inline constexpr int kVtreesItemTagBits = 2;

/// One item of a frame message. kSplit: `left` and `right` (split =
/// left.vid - B) and, for an asset's trees, `wings` (left: the face
/// (vs, vt, vl), right: (vt, vs, vr)); kDown, kUp: `split`; kTraceUpdate:
/// `vertex`, `parent`.
struct VtreesItem {
  VtreesItemKind kind = VtreesItemKind::kSplit;
  uint32_t split = 0;
  uint32_t vertex = 0;
  uint32_t parent = 0;
  VtreesNodeRecord left;
  VtreesNodeRecord right;
  VtreesWing wings[2];
  bool operator==(const VtreesItem& o) const;
};

struct VtreesTreesMessage {
  VtreesWidths widths;
  std::vector<VtreesNodeRecord> base;  ///< B records, vid 0 .. B-1 in order
};

/// The type of a whole message after checking its header: magic, version
/// (newer: kUnsupported), a known type and a length that is the rest of the
/// bytes and at most kMaxVtreesPayloadBytes.
Result<VtreesMessageType> vtrees_message_type(const uint8_t* data, size_t size);

/// Payload: uint32 B, uint32 S, uint8 run count bits, uint8 run length bits,
/// uint8 flags (bit 0: an asset's trees, with wedge data), a zero byte;
/// with the flag, uint32 face slot count and uint32 wedge count (both >= 1);
/// then the B base records' bits (with the flag, each fan pair's face slot
/// and wedge after the fan).
/// \return kInvalidInput when a record does not fit the widths or the rules
///         decode_vtrees_trees() enforces.
Result<Bytes> encode_vtrees_trees(const VtreesTreesMessage& message);
/// Refuses B = 0, B + S >= 2^32 - 1, widths over 32, unknown flags, a zero
/// slot or wedge count with the flag, a pair's slot or wedge out of range, a
/// base record whose
/// vid is not its index, a fan vertex >= B or equal to the node's own, an
/// open run under 2 or a closed run under 3 vertices, non-finite
/// coordinates, nonzero padding, trailing bytes.
Result<VtreesTreesMessage> decode_vtrees_trees(const uint8_t* data, size_t size);

/// Payload: uint32 item count, then per item its 2-bit kind and body:
/// kSplit: left and right record (with wedges: their pairs after each fan),
/// then with wedges per wing a presence bit and, when present, its slot,
/// wedge, change count (id_bits) and changes (vertex id_bits, wedge);
/// kDown / kUp: split id (split_bits);
/// kTraceUpdate: vertex and parent (id_bits each).
Result<Bytes> encode_vtrees_frame(const std::vector<VtreesItem>& items, const VtreesWidths& widths);
/// Besides the record rules of decode_vtrees_trees(): a left vid must be a
/// split vertex B + k, its pid < its vid, the right vid its pid; a fan vertex
/// of split k's nodes must exist at split k (< B + k + 1); trace indices
/// strictly increase below the fan's size, trace parents are below their
/// vertex, which is a split vertex; a split id < S; a trace update's vertex
/// is a split vertex and its parent below it; at most kMaxVtreesItems items;
/// a wing's slot or wedge out of range, its changes not strictly decreasing
/// below the split vertex.
Result<std::vector<VtreesItem>> decode_vtrees_frame(const uint8_t* data, size_t size,
                                                    const VtreesWidths& widths);

/// Payload: the bounding sphere's centre (3 float32) and radius (float32),
/// as mode stream's scene message. The decoder refuses a non-finite value
/// or a radius <= 0.
Bytes encode_vtrees_scene(const BoundingSphere& sphere);
Result<BoundingSphere> decode_vtrees_scene(const uint8_t* data, size_t size);

/// Payload: uint32, the number of frame messages of the whole answer.
Bytes encode_vtrees_end_of_answer(uint32_t messages);
Result<uint32_t> decode_vtrees_end_of_answer(const uint8_t* data, size_t size);

}  // namespace lodbake
