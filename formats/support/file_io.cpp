#include "formats/support/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace lodbake {
namespace {

std::string errno_text() {
  return std::strerror(errno);
}

// Closes the descriptor on every path out of a function.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  int release() {
    int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

}  // namespace

Result<Bytes> read_file(const std::string& path, uint64_t max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer
  // forever; it is refused below, and regular files ignore the flag.
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  if (fd.get() < 0) return io_error("cannot open: " + errno_text());
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return io_error("cannot stat: " + errno_text());
  if (S_ISDIR(st.st_mode)) return io_error("is a directory");
  if (!S_ISREG(st.st_mode)) return io_error("not a regular file");
  const auto size = static_cast<uint64_t>(st.st_size);
  if (size > max_bytes) {
    return invalid_input("file is " + std::to_string(size) + " bytes, more than the limit of " +
                         std::to_string(max_bytes));
  }
  Bytes data(static_cast<size_t>(size));
  size_t done = 0;
  while (done < data.size()) {
    ssize_t got = ::read(fd.get(), data.data() + done, data.size() - done);
    if (got < 0) {
      if (errno == EINTR) continue;
      return io_error("read failed: " + errno_text());
    }
    if (got == 0) return io_error("file shrank while it was read");
    done += static_cast<size_t>(got);
  }
  return data;
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

namespace {

// Writes `data` to a new temporary file beside `path` and returns its name;
// refuses a `path` that exists and is not a regular file.
Result<std::string> write_temporary_beside(const std::string& path, const uint8_t* data,
                                           size_t size) {
  // The rename into place would replace whatever is at `path`: refuse
  // anything but a regular file there, so that `-o /dev/null` run as root or
  // `-o` naming a FIFO never swaps a device node or pipe for a regular file.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return io_error("is a directory");
    if (!S_ISREG(st.st_mode))
      return io_error("not a regular file; outputs replace regular files only");
  }
  std::string temp = path + ".tmp-XXXXXX";
  FileDescriptor fd(::mkstemp(temp.data()));
  if (fd.get() < 0) return io_error("cannot create a temporary file beside it: " + errno_text());
  auto fail = [&](const std::string& what) {
    std::string message = what + ": " + errno_text();
    ::close(fd.release());
    ::unlink(temp.c_str());
    return io_error(message);
  };
  size_t done = 0;
  while (done < size) {
    ssize_t put = ::write(fd.get(), data + done, size - done);
    if (put < 0) {
      if (errno == EINTR) continue;
      return fail("write failed");
    }
    done += static_cast<size_t>(put);
  }
  // mkstemp creates the file 0600; outputs should get the usual permissions.
  mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(fd.get(), 0666 & ~mask) != 0) return fail("cannot set permissions");
  if (::fsync(fd.get()) != 0) return fail("flush failed");
  if (::close(fd.release()) != 0) {
    ::unlink(temp.c_str());
    return io_error("close failed: " + errno_text());
  }
  return temp;
}

Status rename_into_place(const std::string& temp, const std::string& path) {
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    std::string message = "cannot rename the temporary file into place: " + errno_text();
    ::unlink(temp.c_str());
    return io_error(message);
  }
  return Status::ok();
}

}  // namespace

Status write_file_atomic(const std::string& path, const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(std::string temp, write_temporary_beside(path, data, size));
  return rename_into_place(temp, path);
}

StagedOutputs::~StagedOutputs() {
  for (const File& file : files_)
    ::unlink(file.temp.c_str());
}

Status StagedOutputs::stage(const std::string& path, const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(std::string temp, write_temporary_beside(path, data, size));
  files_.push_back({std::move(temp), path});
  return Status::ok();
}

Status StagedOutputs::commit(std::string* failed_path) {
  std::vector<File> files = std::move(files_);
  files_.clear();
  for (size_t i = 0; i < files.size(); ++i) {
    Status renamed = rename_into_place(files[i].temp, files[i].path);
    if (!renamed.is_ok()) {
      for (size_t j = i + 1; j < files.size(); ++j)
        ::unlink(files[j].temp.c_str());
      if (failed_path != nullptr) *failed_path = files[i].path;
      return renamed;
    }
  }
  return Status::ok();
}

}  // namespace lodbake
