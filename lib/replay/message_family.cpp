// The shared message header check (lib/replay/message_family.h). The
// wording of each refusal is the one mode stream's and mode vtrees' own
// header checks gave before they shared this one.
#include "lib/replay/message_family.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "formats/support/byte_reader.h"

namespace lodbake {

Result<uint32_t> message_payload_length(const MessageFamily& family, const uint8_t* header,
                                        size_t size, uint32_t max_payload) {
  const std::string prefix = std::string(family.name) + " message: ";
  auto bad = [&](const std::string& why) { return invalid_input(prefix + why); };
  ByteReader r(header, size);
  uint8_t magic = 0, type = 0;
  uint32_t length = 0;
  if (!r.read(&magic) || !r.read(&type) || !r.read(&length)) {
    return bad("shorter than its " + std::to_string(kMessageHeaderBytes) + "-byte header");
  }
  const int version = magic & 15, known = family.magic_version & 15;
  if ((magic >> 4) != (family.magic_version >> 4)) return bad("bad magic");
  if (version > known) {
    return unsupported(prefix + "version " + std::to_string(version) +
                       " is newer than this reader's " + std::to_string(known));
  }
  if (version != known) return bad("unknown version " + std::to_string(version));
  if (type < 1 || type > family.last_type) return bad("unknown type " + std::to_string(type));
  const uint32_t limit = std::min(max_payload, family.max_payload);
  if (length > limit) {
    return bad("payload of " + std::to_string(length) + " bytes exceeds the limit of " +
               std::to_string(limit));
  }
  return length;
}

Result<uint8_t> message_type(const MessageFamily& family, const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(uint32_t length,
                           message_payload_length(family, data, size, family.max_payload));
  if (length != size - kMessageHeaderBytes) {
    return invalid_input(std::string(family.name) + " message: header says " +
                         std::to_string(length) + " payload bytes, " +
                         std::to_string(size - kMessageHeaderBytes) + " follow");
  }
  return data[1];
}

Bytes frame_message(const MessageFamily& family, uint8_t type, const Bytes& payload) {
  // Sized once and filled in place: appending to an empty vector, once
  // inlined, trips g++ 12's -Wstringop-overflow (a false positive).
  Bytes out(kMessageHeaderBytes + payload.size());
  const auto length = static_cast<uint32_t>(payload.size());
  out[0] = family.magic_version;
  out[1] = type;
  for (int i = 0; i < 4; ++i)
    out[2 + i] = static_cast<uint8_t>(length >> (8 * i));
  std::copy(payload.begin(), payload.end(), out.begin() + kMessageHeaderBytes);
  return out;
}

Result<ByteReader> open_message(const MessageFamily& family, const uint8_t* data, size_t size,
                                uint8_t want, const char* what) {
  LODBAKE_ASSIGN_OR_RETURN(uint8_t type, message_type(family, data, size));
  if (type != want) {
    return invalid_input(std::string(family.name) + " message: type " + std::to_string(type) +
                         " where a " + what + " was expected");
  }
  return ByteReader(data + kMessageHeaderBytes, size - kMessageHeaderBytes);
}

Bytes sphere_payload(const BoundingSphere& sphere) {
  Bytes payload;
  payload.reserve(16);
  ByteWriter w(&payload);
  for (float c : sphere.center)
    w.write(c);
  w.write(sphere.radius);
  return payload;
}

Result<BoundingSphere> decode_sphere_payload(const MessageFamily& family, ByteReader r) {
  auto bad = [&](const char* why) {
    return invalid_input(std::string(family.name) + " message: " + why);
  };
  if (r.remaining() != 16) return bad("a scene message has 16 payload bytes");
  BoundingSphere s;
  for (float& c : s.center) {
    r.read(&c);
    if (!std::isfinite(c)) return bad("the scene's centre is not finite");
  }
  r.read(&s.radius);
  if (!(s.radius > 0) || !std::isfinite(s.radius)) return bad("the scene's radius is not positive");
  return s;
}

}  // namespace lodbake
