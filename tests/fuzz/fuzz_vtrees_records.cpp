// Fuzz target for the vertex-tree message decoders and client
// (lib/replay/vtrees_records.h, lib/replay/vtrees_client.h). The input is a
// session's downlink: messages back to back, each as long as its header
// says (the last one takes what remains). A first trees message starts a
// client, and every later message is decoded under its widths and applied
// to it (an asset's client also finds its corners' wedges); a first frame
// message is decoded under four fixed width contexts, the last one Fox's
// trees with wedges (tests/unit/vtrees_wedges_test.cpp checks them);
// scene and end-of-answer messages (a connection's) are decoded anywhere.
// Whatever decodes must re-encode to the same bytes (one encoding per
// message); the client may refuse anything, never crash.
#include <cstdint>
#include <optional>

#include "lib/replay/vtrees_client.h"
#include "lib/replay/vtrees_records.h"
#include "tests/fuzz/fuzz_section_checks.h"

namespace {

using namespace lodbake;
using lodbake::fuzz::require;
using lodbake::fuzz::require_same_bytes;

void check_frame(const uint8_t* data, size_t size, const VtreesWidths& widths) {
  Result<std::vector<VtreesItem>> items = decode_vtrees_frame(data, size, widths);
  if (!items.is_ok()) return;
  Result<Bytes> again = encode_vtrees_frame(items.value(), widths);
  require(again.is_ok(), "decoded frame message cannot be encoded");
  require_same_bytes(again.value(), data, size, "frame round trip");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::optional<VtreesClient> client;
  bool first = true;
  while (size > 0) {
    size_t length = size;
    if (size >= kVtreesHeaderBytes) {
      const uint64_t payload = uint64_t{data[2]} | uint64_t{data[3]} << 8 |
                               uint64_t{data[4]} << 16 | uint64_t{data[5]} << 24;
      if (payload + kVtreesHeaderBytes < size) length = payload + kVtreesHeaderBytes;
    }
    Result<VtreesMessageType> type = vtrees_message_type(data, length);
    if (!type.is_ok()) {
      require(type.status().kind() == ErrorKind::kInvalidInput ||
                  type.status().kind() == ErrorKind::kUnsupported,
              "header refused with an unexpected kind");
    } else if (type.value() == VtreesMessageType::kScene) {
      Result<BoundingSphere> sphere = decode_vtrees_scene(data, length);
      if (sphere.is_ok()) {
        require_same_bytes(encode_vtrees_scene(sphere.value()), data, length, "scene round trip");
      }
    } else if (type.value() == VtreesMessageType::kEndOfAnswer) {
      Result<uint32_t> count = decode_vtrees_end_of_answer(data, length);
      if (count.is_ok()) {
        require_same_bytes(encode_vtrees_end_of_answer(count.value()), data, length,
                           "end of answer round trip");
      }
    } else if (type.value() == VtreesMessageType::kTrees) {
      Result<VtreesTreesMessage> trees = decode_vtrees_trees(data, length);
      if (trees.is_ok()) {
        Result<Bytes> again = encode_vtrees_trees(trees.value());
        require(again.is_ok(), "decoded trees message cannot be encoded");
        require_same_bytes(again.value(), data, length, "trees round trip");
        if (first) {
          Result<VtreesClient> created = VtreesClient::create(data, length);
          if (created.is_ok()) client.emplace(std::move(created).value());
        }
      }
    } else if (client) {
      check_frame(data, length, client->widths());
      if (client->receive(data, length).is_ok()) {
        (void)client->triangles();
        if (client->has_wedges()) (void)client->corner_wedges();
      } else {
        client.reset();  // the state after an error is undefined
      }
    } else if (first) {
      const VtreesWidths contexts[4] = {
          {7, 20, 1, 3}, {1, 0, 0, 0}, {300, 70000, 2, 5}, {4, 286, 1, 4, 576, 434}};
      for (const VtreesWidths& w : contexts)
        check_frame(data, length, w);
    }
    first = false;
    data += length;
    size -= length;
  }
  return 0;
}
