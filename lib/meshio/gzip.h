// gzip decompression for compressed mesh files (e.g. the Stanford .ply.gz
// models), through zlib, with a hard bound on the decompressed size so that a
// small hostile file cannot make the reader allocate without limit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

// Largest output gunzip() produces unless told otherwise (4 GiB).
constexpr uint64_t kDefaultGunzipLimit = uint64_t{1} << 32;

/// True when `bytes` starts with the gzip magic (1f 8b).
bool is_gzip(const Bytes& bytes);
bool is_gzip(const uint8_t* data, size_t size);

/// Decompresses a gzip file of `size` bytes at `data` (several concatenated
/// members are decompressed one after the other, as `gzip -d` does).
/// \return the decompressed bytes, or kInvalidInput when the input is not
///   gzip, is corrupt or truncated, has trailing bytes that are not another
///   gzip member, or decompresses to more than `max_output` bytes; kRuntime
///   when memory runs out.
Result<Bytes> gunzip(const uint8_t* data, size_t size, uint64_t max_output = kDefaultGunzipLimit);

}  // namespace lodbake
