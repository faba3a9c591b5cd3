// Fuzz target for the compact FANH decoder (codec 1). Input: a u32 byte
// count n, n bytes of a raw BASE payload, then the compact FANH payload
// decoded against that BASE (the corpus holds real pairs written by
// lodbake-pack). Invariants: the decoder refuses only with LBK-E023 (or a
// runtime error for an allocation it cannot make); what it accepts is a
// raw FANH payload the raw reader accepts, which encodes compactly again
// and decodes to the same bytes.
#include <cstdint>
#include <cstring>

#include "formats/sections/base.h"
#include "formats/sections/fanh.h"
#include "formats/sections/fanh_compact.h"
#include "tests/fuzz/fuzz_section_checks.h"

using namespace lodbake;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  uint32_t base_size = 0;
  if (size < 4) return 0;
  std::memcpy(&base_size, data, 4);
  if (base_size > size - 4) return 0;
  Result<TriangleMesh> base = decode_base(data + 4, base_size);
  if (!base.is_ok()) return 0;
  const uint8_t* payload = data + 4 + base_size;
  const size_t payload_size = size - 4 - base_size;
  Result<Bytes> raw = decode_fanh_compact(payload, payload_size, base.value());
  if (!raw.is_ok()) {
    fuzz::require_decode_error(raw.status(), "compact FANH decode error without LBK-E023");
    return 0;
  }
  fuzz::require(decode_fanh(raw.value().data(), raw.value().size()).is_ok(),
                "compact FANH decodes to a payload the raw reader refuses");
  Result<Bytes> again = encode_fanh_compact(raw.value().data(), raw.value().size(), base.value());
  fuzz::require(again.is_ok(), "a decoded compact FANH payload does not encode");
  Result<Bytes> back =
      decode_fanh_compact(again.value().data(), again.value().size(), base.value());
  fuzz::require(back.is_ok() && back.value() == raw.value(), "compact FANH round trip differs");
  return 0;
}
