// The corruptions every message decoder of the replay wire formats (mode
// stream's packets, mode vtrees' records) must refuse, shared by their
// tests: every truncation, every bit flip in the header, a trailing byte,
// and a trailing byte the length field agrees with.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"

namespace lodbake {

/// `decodes(bytes)` is true when the decoder of `message`'s kind accepts
/// `bytes`; `message` itself must be accepted.
template <typename Decodes>
void expect_refuses_corruptions(const Bytes& message, size_t header_bytes, Decodes decodes) {
  ASSERT_TRUE(decodes(message));
  for (size_t n = 0; n < message.size(); ++n) {
    const Bytes cut(message.begin(), message.begin() + static_cast<ptrdiff_t>(n));
    EXPECT_FALSE(decodes(cut)) << "accepted " << n << " of " << message.size();
  }
  for (size_t bit = 0; bit < header_bytes * 8; ++bit) {
    Bytes flipped = message;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(decodes(flipped)) << "accepted a flip of header bit " << bit;
  }
  Bytes longer = message;
  longer.push_back(0);
  EXPECT_FALSE(decodes(longer));
  longer[2] = static_cast<uint8_t>(longer[2] + 1);  // the length agrees, the payload does not
  EXPECT_FALSE(decodes(longer));
}

}  // namespace lodbake
