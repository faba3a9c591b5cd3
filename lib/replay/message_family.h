// The framing both replay wire formats share (issue 9): mode stream's
// messages (lib/replay/stream_packets.h) and mode vtrees' messages
// (lib/replay/vtrees_records.h) open with the same 6-byte header,
//
//   byte 0      magic and version: high nibble = the family, low nibble =
//               its version
//   byte 1      type, 1 .. the family's last type
//   bytes 2-5   payload length, uint32 little-endian
//
// and differ only in the magic, the known types and the payload limit. A
// MessageFamily names those, so one header check serves both decoders and
// a transport (lib/replay/stream_transport.h) checks the family it was
// built to receive before it allocates a payload.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/status.h"

namespace lodbake {

inline constexpr size_t kMessageHeaderBytes = 6;

struct MessageFamily {
  /// What error messages call it: "<name> message: ...".
  const char* name = "";
  /// Byte 0: the family (high nibble) and the newest version this reader
  /// knows (low nibble).
  uint8_t magic_version = 0;
  /// Known types are 1 .. last_type.
  uint8_t last_type = 0;
  /// The largest payload the family's decoders take.
  uint32_t max_payload = 0;
};

/// The payload length a header announces, from its first
/// kMessageHeaderBytes alone: the family's magic, its version (newer:
/// kUnsupported; older: kInvalidInput), a known type, and a length at most
/// min(max_payload, family.max_payload). Refusals are kInvalidInput
/// "<name> message: ...", so a peer announcing a huge message or speaking
/// another family is refused before anything is allocated for it.
Result<uint32_t> message_payload_length(const MessageFamily& family, const uint8_t* header,
                                        size_t size, uint32_t max_payload);

/// The same for a whole message, whose length must be the rest of `size`;
/// returns the type byte.
Result<uint8_t> message_type(const MessageFamily& family, const uint8_t* data, size_t size);

}  // namespace lodbake
