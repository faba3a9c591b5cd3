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

// Checks, before a run does its work, that `path` can be written as an output:
// fails with kIo when it exists and is not a regular file (a folder, a device
// such as /dev/full or /dev/null, a FIFO), or when its folder is missing or
// not writable. Writing checks the same again (the file system may change).
Status check_output_path(const std::string& path);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the temporary
// files of the writes in progress (write_file_atomic(), StagedOutputs) and
// then end the process by the same signal with its default action, so that
// its exit status still says it was killed by that signal. A signal ignored
// when this is called (nohup) stays ignored. Call once at start-up, before
// starting threads; calling it again does nothing.
void remove_temporaries_on_signals();

// Writes `data` to `path` through a temporary file in the same directory that
// is renamed over `path` only after everything was written and flushed, so a
// failed run never leaves a partial output behind: a failed write, flush or
// rename (a full disk, an I/O error) removes the temporary file and fails
// with kIo. Fails with kIo, before writing anything, when `path` exists and
// is not a regular file (a folder, a device such as /dev/full, a FIFO): the
// rename would replace it.
Status write_file_atomic(const std::string& path, const uint8_t* data, size_t size);
inline Status write_file_atomic(const std::string& path, const Bytes& data) {
  return write_file_atomic(path, data.data(), data.size());
}
inline Status write_file_atomic(const std::string& path, const std::string& data) {
  return write_file_atomic(path, reinterpret_cast<const uint8_t*>(data.data()), data.size());
}

// The outputs of a run that writes several files, written all or none: stage()
// writes each to a temporary file beside its path (refusing what
// write_file_atomic refuses), and only commit() renames them into place, in
// the order staged. Temporary files not committed are removed when the object
// is destroyed, so a run that fails before commit() leaves no output at all.
class StagedOutputs {
 public:
  StagedOutputs() = default;
  ~StagedOutputs();
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;

  Status stage(const std::string& path, const uint8_t* data, size_t size);
  Status stage(const std::string& path, const Bytes& data) {
    return stage(path, data.data(), data.size());
  }
  // Renames every staged file into place. When a rename fails, `*failed_path`
  // (when given) names that output and the remaining temporary files are
  // removed; the outputs renamed before it stay.
  Status commit(std::string* failed_path = nullptr);

 private:
  struct File {
    std::string temp;
    std::string path;
  };
  std::vector<File> files_;
};

}  // namespace lodbake
