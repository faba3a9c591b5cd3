// Whole-file reads and atomic whole-file writes. Every lodbake reader parses
// from memory, so that the same code serves files, tests and fuzzers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/status.h"

namespace lodbake {

using Bytes = std::vector<uint8_t>;

// Reads the whole file. Fails with kIo when it cannot be opened or read, and
// with kInvalidInput when it is larger than `max_bytes` (a guard against
// pointing a tool at a device or a multi-gigabyte file by mistake).
Result<Bytes> read_file(const std::string& path, uint64_t max_bytes = uint64_t{1} << 34);

// True when both paths name the same existing file (same device and inode),
// e.g. an output that would overwrite its own input.
bool same_file(const std::string& a, const std::string& b);

// Writes `data` to `path` through a temporary file in the same directory that
// is renamed over `path` only after everything was written and flushed, so a
// failed run never leaves a partial output behind. Fails with kIo, before
// writing anything, when `path` exists and is not a regular file (a folder, a
// device such as /dev/null, a FIFO): the rename would replace it.
Status write_file_atomic(const std::string& path, const uint8_t* data, size_t size);
inline Status write_file_atomic(const std::string& path, const Bytes& data) {
  return write_file_atomic(path, data.data(), data.size());
}
inline Status write_file_atomic(const std::string& path, const std::string& data) {
  return write_file_atomic(path, reinterpret_cast<const uint8_t*>(data.data()), data.size());
}

}  // namespace lodbake
