// The checks of the compact-codec fuzz targets (one per decoder,
// formats/sections/compact_sections.h): the decoder refuses only with
// LBK-E023 (or a runtime error for an allocation it cannot make), and what
// it accepts is a valid raw payload (the encoder decodes it with the kind's
// raw reader first) that encodes and decodes back to itself.
#pragma once

#include <cstddef>
#include <cstdint>

#include <cstring>

#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "tests/fuzz/fuzz_section_checks.h"

namespace lodbake::fuzz {

inline void check_compact_section(const char* tag, const uint8_t* data, size_t size) {
  Result<Bytes> raw = decode_section_compact(tag, data, size);
  if (!raw.is_ok()) {
    require_decode_error(raw.status(), "compact decode error without LBK-E023");
    return;
  }
  Result<Bytes> again = encode_section_compact(tag, raw.value().data(), raw.value().size());
  require(again.is_ok(), "a decoded compact payload is not a raw payload the codec accepts");
  Result<Bytes> back = decode_section_compact(tag, again.value().data(), again.value().size());
  require(back.is_ok() && back.value() == raw.value(), "compact round trip differs");
}

// The same for a codec coded against BASE (FANH, STRP). Input: a u32 byte
// count n, n bytes of a raw BASE payload, then the compact payload decoded
// against that BASE (the corpora hold real pairs written by lodbake-pack).
inline void check_base_compact_section(const char* tag, const uint8_t* data, size_t size) {
  uint32_t base_size = 0;
  if (size < 4) return;
  std::memcpy(&base_size, data, 4);
  if (base_size > size - 4) return;
  Result<TriangleMesh> base = decode_base(data + 4, base_size);
  if (!base.is_ok()) return;
  const uint8_t* payload = data + 4 + base_size;
  const size_t payload_size = size - 4 - base_size;
  Result<Bytes> raw = decode_section_compact(tag, payload, payload_size, base.value());
  if (!raw.is_ok()) {
    require_decode_error(raw.status(), "compact decode error without LBK-E023");
    return;
  }
  Result<Bytes> again =
      encode_section_compact(tag, raw.value().data(), raw.value().size(), base.value());
  require(again.is_ok(), "a decoded compact payload is not a raw payload the codec accepts");
  Result<Bytes> back =
      decode_section_compact(tag, again.value().data(), again.value().size(), base.value());
  require(back.is_ok() && back.value() == raw.value(), "compact round trip differs");
}

}  // namespace lodbake::fuzz
