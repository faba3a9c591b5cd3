// Compact RFIN (codec 1): a lossless recoding of a raw RFIN payload, layout
// in docs/format.md "Compact RFIN". RFIN's records (Hoppe 1997's
// view-dependent refinement terms: sphere radius, mu^2, delta^2, and a
// quantized cone of normals) are 18 bytes per split, in VHIE's node order.
//
// Choices, measured on the Stanford bunny's records (34819 splits, raw 144
// bits per split), as mean log2 of the difference from a prediction:
// - Floats as bit-pattern differences from the previous record's: radius
//   21.4, mu^2 24.0, delta^2 24.4 bits. The parent's record predicts mu^2
//   better (20.2) and the others no better, and needs VHIE's structure: the
//   codec stays on its own section, at a cost of about 4 bits per split.
// - Cone axis x, y and half-angle as zigzag differences of the 16-bit
//   values from the previous record's: 11.3, 11.3, 10.9 bits (the parent's
//   axis: 9.7).
// - One Exp-Golomb context per field, the order chosen by the encoder.
// The floats' mantissas are mostly noise, so most of the payload stays:
// this codec trims exponents and high bits, not the values.
#include "formats/sections/rfin_compact.h"

#include <cinttypes>
#include <cstring>
#include <new>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/compact_coding.h"
#include "formats/sections/rfin.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

// Per record: radius, mu^2, delta^2 bit patterns, axis x, axis y, angle.
constexpr int kFields = 6;
constexpr int kFieldBits[kFields] = {32, 32, 32, 16, 16, 16};

Status bad_compact(const std::string& detail) {
  return malformed_section(kRfinTag, "compact: " + detail);
}

// The raw records as rows of kFields values.
std::vector<uint32_t> read_records(const uint8_t* raw, uint32_t splits) {
  std::vector<uint32_t> values(size_t{splits} * kFields);
  const uint8_t* floats = raw + kRfinFixedBytes;
  BitReader cones(floats + 12 * size_t{splits}, 6 * size_t{splits});
  for (size_t i = 0; i < splits; ++i) {
    std::memcpy(&values[kFields * i], floats + 12 * i, 12);
    for (int f = 3; f < kFields; ++f)
      cones.read(16, &values[kFields * i + f]);
  }
  return values;
}

Bytes write_raw(uint32_t splits, const std::vector<uint32_t>& values) {
  Bytes out(kRfinFixedBytes + 12 * size_t{splits});
  std::memcpy(out.data(), &splits, 4);
  for (size_t i = 0; i < splits; ++i)
    std::memcpy(out.data() + kRfinFixedBytes + 12 * i, &values[kFields * i], 12);
  BitWriter bits(&out);
  for (size_t i = 0; i < splits; ++i) {
    for (int f = 3; f < kFields; ++f)
      bits.write(values[kFields * i + f], 16);
  }
  bits.finish();
  return out;
}

void encode_pass(uint32_t splits, const std::vector<uint32_t>& values, CompactStreamWriter* out) {
  for (size_t i = 0; i < splits; ++i) {
    for (int f = 0; f < kFields; ++f) {
      const uint32_t previous = i == 0 ? 0 : values[kFields * (i - 1) + f];
      out->golomb(f, zigzag64(int64_t{values[kFields * i + f]} - int64_t{previous}));
    }
  }
}

}  // namespace

Result<Bytes> encode_rfin_compact(const uint8_t* raw, size_t raw_size) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(uint32_t splits, read_rfin_summary(raw, raw_size));
    const std::vector<uint32_t> values = read_records(raw, splits);
    Bytes out(1 + 4);
    out[0] = kRfinCompactVersion;
    std::memcpy(out.data() + 1, &splits, 4);
    CompactStreamWriter stream(kFields);
    encode_pass(splits, values, &stream);
    stream.write_to(&out);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding compact RFIN");
  }
}

Result<Bytes> decode_rfin_compact(const uint8_t* data, size_t size) {
  try {
    if (size < 5) {
      return bad_compact(string_printf("%zu bytes, the version and split count need 5", size));
    }
    if (data[0] != kRfinCompactVersion)
      return bad_compact(string_printf("unknown layout version %u", data[0]));
    uint32_t splits = 0;
    std::memcpy(&splits, data + 1, 4);
    CompactStreamReader in;
    if (!in.start(data + 5, size - 5, kFields))
      return bad_compact("missing or out-of-range Exp-Golomb orders");
    if (uint64_t{splits} * kFields > in.bits_left()) {
      return bad_compact(string_printf("%u records need at least %" PRIu64 " bits, %" PRIu64
                                       " remain",
                                       splits, uint64_t{splits} * kFields, in.bits_left()));
    }
    std::vector<uint32_t> values(size_t{splits} * kFields);
    uint64_t code = 0;
    for (size_t i = 0; i < splits; ++i) {
      for (int f = 0; f < kFields; ++f) {
        const uint32_t previous = i == 0 ? 0 : values[kFields * (i - 1) + f];
        if (!in.golomb(f, &code))
          return bad_compact(string_printf("record %zu: truncated or malformed code", i));
        const int64_t v = int64_t{previous} + unzigzag64(code);
        if (v < 0 || v >= (int64_t{1} << kFieldBits[f]))
          return bad_compact(string_printf("record %zu: value out of range", i));
        values[kFields * i + f] = static_cast<uint32_t>(v);
      }
    }
    if (!in.at_clean_end())
      return bad_compact("nonzero padding or trailing bytes after the stream");
    return write_raw(splits, values);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding compact RFIN");
  }
}

}  // namespace lodbake
