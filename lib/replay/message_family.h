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

#include "formats/support/byte_reader.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"

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

/// A whole message of `family`: the header for `type` and `payload`.
Bytes frame_message(const MessageFamily& family, uint8_t type, const Bytes& payload);

/// The payload of a whole message of `family` whose type must be `want`;
/// otherwise "<name> message: type T where a <what> was expected".
Result<ByteReader> open_message(const MessageFamily& family, const uint8_t* data, size_t size,
                                uint8_t want, const char* what);

/// The scene message's payload both families send a client first: the
/// bounding sphere its camera paths are placed around, 16 bytes (centre,
/// radius, float32 little-endian).
Bytes sphere_payload(const BoundingSphere& sphere);
/// Its strict decoder: exactly 16 bytes, a finite centre, a positive finite
/// radius; refusals are "<name> message: ...".
Result<BoundingSphere> decode_sphere_payload(const MessageFamily& family, ByteReader payload);

}  // namespace lodbake
