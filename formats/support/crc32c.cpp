// CRC-32C (Castagnoli 1993), table driven, slicing-by-8 (Kounavis and Berry,
// "A Systematic Approach to Building High Performance Software-based CRC
// Generators", 2005): eight 256-entry tables let the loop consume eight bytes
// per step with independent lookups.
//
// lodbake carries its own implementation because formats/ may depend only on
// the C++ standard library, Draco and nlohmann-json, none of which exports a
// CRC-32C. No hardware (SSE4.2) path: the checksum is a small part of a bake,
// and one portable path is one thing to test.
#include "formats/support/crc32c.h"

#include <array>
#include <cstring>

namespace lodbake {
namespace {

constexpr uint32_t kPolynomial = 0x82F63B78u;  // 0x1EDC6F41 bit-reversed

using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr Tables make_tables() {
  Tables t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t crc = i;
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc >> 1) ^ ((crc & 1u) ? kPolynomial : 0u);
    t[0][i] = crc;
  }
  // t[k][i] is the CRC of byte i followed by k zero bytes.
  for (uint32_t i = 0; i < 256; ++i) {
    for (int k = 1; k < 8; ++k)
      t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFFu];
  }
  return t;
}

constexpr Tables kTables = make_tables();

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the word loop assumes a little-endian host");

}  // namespace

uint32_t crc32c_extend(uint32_t crc, const uint8_t* data, size_t size) {
  uint32_t c = ~crc;
  // Byte at a time until the pointer is 8-byte aligned; the bulk loop then
  // reads aligned words (memcpy keeps it free of aliasing questions).
  while (size != 0 && (reinterpret_cast<uintptr_t>(data) & 7u) != 0) {
    c = (c >> 8) ^ kTables[0][(c ^ *data) & 0xFFu];
    ++data;
    --size;
  }
  while (size >= 8) {
    uint32_t lo;
    uint32_t hi;
    std::memcpy(&lo, data, 4);
    std::memcpy(&hi, data + 4, 4);
    lo ^= c;
    c = kTables[7][lo & 0xFFu] ^ kTables[6][(lo >> 8) & 0xFFu] ^ kTables[5][(lo >> 16) & 0xFFu] ^
        kTables[4][lo >> 24] ^ kTables[3][hi & 0xFFu] ^ kTables[2][(hi >> 8) & 0xFFu] ^
        kTables[1][(hi >> 16) & 0xFFu] ^ kTables[0][hi >> 24];
    data += 8;
    size -= 8;
  }
  while (size != 0) {
    c = (c >> 8) ^ kTables[0][(c ^ *data) & 0xFFu];
    ++data;
    --size;
  }
  return ~c;
}

uint32_t crc32c(const uint8_t* data, size_t size) {
  return crc32c_extend(0, data, size);
}

}  // namespace lodbake
