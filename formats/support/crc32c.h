// CRC-32C (Castagnoli): the checksum of the lodbake container's header,
// section table and sections.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lodbake {

/// CRC-32C of `size` bytes at `data` (reflected polynomial 0x82F63B78,
/// initial value 0xFFFFFFFF, final XOR 0xFFFFFFFF; the iSCSI / ext4 / SSE4.2
/// `crc32` checksum). crc32c("123456789") == 0xE3069283.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
uint32_t crc32c(const uint8_t* data, size_t size);

/// Continues a checksum: crc32c_extend(crc32c(a), b) == crc32c(a followed by b),
/// and crc32c_extend(0, x) == crc32c(x).
uint32_t crc32c_extend(uint32_t crc, const uint8_t* data, size_t size);

/// Incremental form for data that arrives in pieces.
class Crc32c {
 public:
  void update(const uint8_t* data, size_t size) { crc_ = crc32c_extend(crc_, data, size); }
  /// The checksum of everything passed to update() so far.
  uint32_t value() const { return crc_; }

 private:
  uint32_t crc_ = 0;
};

}  // namespace lodbake
