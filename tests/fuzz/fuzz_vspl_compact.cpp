// Fuzz target for the compact VSPL decoder (codec 1). Input: a u32 byte
// count n, n bytes of a raw BASE payload, then the compact VSPL payload
// decoded against that BASE (the corpus holds real pairs written by
// lodbake-pack, in every layout version). Invariant: when the result is a
// valid raw VSPL payload, encoding it compactly again in the input's layout
// version (and in the writer's default choice) and decoding gives the same
// raw bytes.
#include <cstdint>
#include <cstring>

#include "formats/sections/base.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vspl_compact.h"
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
  Result<Bytes> raw = decode_vspl_compact(payload, payload_size, base.value());
  if (!raw.is_ok()) return 0;
  if (!decode_vspl(raw.value().data(), raw.value().size(), base.value().positions).is_ok())
    return 0;
  for (uint8_t version : {payload[0], uint8_t{0}}) {
    VsplCompactOptions options;
    options.version = version;
    Result<Bytes> again =
        encode_vspl_compact(raw.value().data(), raw.value().size(), base.value(), options);
    fuzz::require(again.is_ok(), "a valid raw VSPL payload does not encode compactly");
    Result<Bytes> back =
        decode_vspl_compact(again.value().data(), again.value().size(), base.value());
    fuzz::require(back.is_ok() && back.value() == raw.value(), "compact VSPL round trip differs");
  }
  return 0;
}
