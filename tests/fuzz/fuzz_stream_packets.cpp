// Fuzz target for the stream message decoders (lib/replay/stream_packets.h).
// The input is one whole message. It is decoded as its header's type says;
// vsplit messages under three id-width contexts (roots, depth): (15, 16),
// (18, 11) and (1, 40), so 0-bit tree ids and ids over 32 bits are covered.
// Whatever decodes must re-encode to the same bytes (one encoding per
// message), and a client fed a decoded base message must start. An asset's
// vsplit messages (wedge data after each packet) decode under Fox's
// widths: 4 roots, depth 8, 434 wedges, 4 base faces (stream_wedges_test
// checks them and writes the seeds). Resume
// messages decode under the same three contexts, each with a server bound
// on the leaf count; a decoded one must agree with resume_leaf_count().
#include <cstdint>

#include "formats/support/bit_packing.h"
#include "lib/replay/stream_client.h"
#include "lib/replay/stream_packets.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using lodbake::fuzz::require;
  using lodbake::fuzz::require_same_bytes;
  Result<StreamMessageType> type = stream_message_type(data, size);
  if (!type.is_ok()) {
    require(type.status().kind() == ErrorKind::kInvalidInput ||
                type.status().kind() == ErrorKind::kUnsupported,
            "header refused with an unexpected kind");
    return 0;
  }
  switch (type.value()) {
    case StreamMessageType::kView: {
      Result<ViewRequest> v = decode_view_request(data, size);
      if (v.is_ok()) {
        require_same_bytes(encode_view_request(v.value()), data, size, "view round trip");
      }
      break;
    }
    case StreamMessageType::kBase: {
      Result<BaseMessage> b = decode_base_message(data, size);
      if (b.is_ok()) {
        Result<Bytes> again = encode_base_message(b.value());
        require(again.is_ok(), "decoded base message cannot be encoded");
        require_same_bytes(again.value(), data, size, "base round trip");
        // The client may refuse a base mesh (a repeated index), never crash.
        (void)StreamClient::create(data, size);
      }
      break;
    }
    case StreamMessageType::kVsplits: {
      const uint32_t contexts[3][2] = {{15, 16}, {18, 11}, {1, 40}};
      for (const auto& c : contexts) {
        StreamIdWidths widths;
        widths.tree_bits = bits_for_count(c[0]);
        widths.node_bits = static_cast<int>(c[1]);
        Result<std::vector<VsplitPacket>> p = decode_vsplit_message(data, size, widths, c[0]);
        if (!p.is_ok()) continue;
        Result<Bytes> again = encode_vsplit_message(p.value(), widths, c[0]);
        require(again.is_ok(), "decoded vsplit message cannot be encoded");
        require_same_bytes(again.value(), data, size, "vsplit round trip");
      }
      StreamIdWidths asset;
      asset.tree_bits = bits_for_count(4);
      asset.node_bits = 8;
      asset.wedges = 434;
      asset.base_faces = 4;
      Result<std::vector<VsplitPacket>> p = decode_vsplit_message(data, size, asset, 4);
      if (p.is_ok()) {
        Result<Bytes> again = encode_vsplit_message(p.value(), asset, 4);
        require(again.is_ok(), "decoded vsplit message with wedges cannot be encoded");
        require_same_bytes(again.value(), data, size, "vsplit with wedges round trip");
      }
      break;
    }
    case StreamMessageType::kResume: {
      const uint32_t contexts[3][2] = {{15, 16}, {18, 11}, {1, 40}};
      Result<uint32_t> count = resume_leaf_count(data, size);
      for (const auto& c : contexts) {
        StreamIdWidths widths;
        widths.tree_bits = bits_for_count(c[0]);
        widths.node_bits = static_cast<int>(c[1]);
        Result<std::vector<HierarchyNodeId>> leaves =
            decode_resume_message(data, size, widths, c[0], uint64_t{1} << 20);
        if (!leaves.is_ok()) continue;
        require(count.is_ok() && count.value() == leaves.value().size(),
                "resume leaf count disagrees with the decoded leaves");
        Result<Bytes> again = encode_resume_message(leaves.value(), widths, c[0]);
        require(again.is_ok(), "decoded resume message cannot be encoded");
        require_same_bytes(again.value(), data, size, "resume round trip");
      }
      break;
    }
    case StreamMessageType::kScene: {
      Result<BoundingSphere> s = decode_scene_message(data, size);
      if (s.is_ok()) {
        require_same_bytes(encode_scene_message(s.value()), data, size, "scene round trip");
      }
      break;
    }
    case StreamMessageType::kEndOfAnswer: {
      Result<uint32_t> n = decode_end_of_answer(data, size);
      if (n.is_ok())
        require_same_bytes(encode_end_of_answer(n.value()), data, size, "end round trip");
      break;
    }
  }
  return 0;
}
