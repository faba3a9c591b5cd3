// "512M", "2G": the sizes --memory-limit takes.
#pragma once

#include <cstdint>
#include <string>

#include "formats/support/status.h"

namespace lodbake {

/// Parses a byte count: a whole number with an optional binary suffix K, M,
/// G or T (powers of 1024; a trailing B or iB is allowed: 512M, 512MB,
/// 512MiB). Fails (kInvalidInput) on anything else, zero, or more than
/// 2^50 bytes.
Result<uint64_t> parse_memory_size(const std::string& text);

}  // namespace lodbake
