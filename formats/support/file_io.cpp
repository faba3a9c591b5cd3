#include "formats/support/file_io.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

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

// The temporary files being written, for the signal handler to remove. Nodes
// are never freed (a finished write frees its node for the next one), so the
// handler may walk the list at any moment without a lock; the list only
// grows at its head, and a node's `next` never changes once published. A
// node's path is written only while the node is kClaimed, under
// `registry_mutex`; the handler reads it only after moving the node from
// kLive to kRemoving, which stops unregister_temporary() from reusing it.
enum NodeState : int { kFree, kClaimed, kLive, kRemoving };

struct TemporaryNode {
  std::atomic<int> state{kClaimed};
  std::string path;  // reserved once; reassigned only when it fits
  TemporaryNode* next = nullptr;
};

std::atomic<TemporaryNode*> temporaries{nullptr};
std::mutex registry_mutex;
// Threads between creating a temporary file and registering it; the handler
// waits for them (signals are blocked in those threads meanwhile).
std::atomic<int> registering{0};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");
static_assert(std::atomic<TemporaryNode*>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

sigset_t cleanup_signal_set() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : kCleanupSignals)
    sigaddset(&set, sig);
  return set;
}

// Blocks SIGINT, SIGTERM and SIGHUP in this thread from creating a temporary
// file until it is registered, so that no signal lands in between.
class RegistrationWindow {
 public:
  RegistrationWindow() {
    registering.fetch_add(1);
    sigset_t set = cleanup_signal_set();
    ::pthread_sigmask(SIG_BLOCK, &set, &saved_);
  }
  ~RegistrationWindow() {
    registering.fetch_sub(1);
    ::pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
  }
  RegistrationWindow(const RegistrationWindow&) = delete;
  RegistrationWindow& operator=(const RegistrationWindow&) = delete;

 private:
  sigset_t saved_;
};

void register_temporary(const std::string& temp) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (TemporaryNode* node = temporaries.load(); node != nullptr; node = node->next) {
    int expected = kFree;
    if (node->path.capacity() >= temp.size() &&
        node->state.compare_exchange_strong(expected, kClaimed)) {
      node->path.assign(temp);  // fits: no reallocation under the handler's eyes
      node->state.store(kLive);
      return;
    }
  }
  auto* node = new TemporaryNode;  // never freed, see above
  node->path.reserve(std::max<size_t>(temp.size(), 255));
  node->path.assign(temp);
  node->next = temporaries.load();
  node->state.store(kLive);
  temporaries.store(node);
}

// After the temporary file was renamed or removed.
void unregister_temporary(const std::string& temp) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (TemporaryNode* node = temporaries.load(); node != nullptr; node = node->next) {
    if (node->state.load() != kLive || node->path != temp) continue;
    int expected = kLive;
    // Fails only when the handler took the node: the process is ending.
    node->state.compare_exchange_strong(expected, kFree);
    return;
  }
}

// Removes every registered temporary file, then ends the process by the same
// signal with its default action, so that the exit status says so. Uses
// only async-signal-safe calls (nanosleep, unlink, signal, raise) and
// lock-free atomics.
void remove_temporaries_and_reraise(int sig) {
  // Another thread may be between creating a file and registering it (its
  // signals are blocked meanwhile): give it up to a second.
  for (int i = 0; i < 1000 && registering.load() > 0; ++i) {
    struct timespec millisecond {
      0, 1000000
    };
    ::nanosleep(&millisecond, nullptr);
  }
  for (TemporaryNode* node = temporaries.load(); node != nullptr; node = node->next) {
    int expected = kLive;
    if (node->state.compare_exchange_strong(expected, kRemoving)) ::unlink(node->path.c_str());
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered with the default action when the handler returns
}

// Refuses an existing `path` that is not a regular file.
Status check_output_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return io_error("is a directory");
    if (!S_ISREG(st.st_mode))
      return io_error("not a regular file; outputs replace regular files only");
  }
  return Status::ok();
}

// Writes `data` to a new temporary file beside `path` and returns its name,
// registered for removal on a signal; refuses a `path` that exists and is
// not a regular file.
Result<std::string> write_temporary_beside(const std::string& path, const uint8_t* data,
                                           size_t size) {
  // The rename into place would replace whatever is at `path`: refuse
  // anything but a regular file there, so that `-o /dev/null` run as root or
  // `-o` naming a FIFO never swaps a device node or pipe for a regular file.
  LODBAKE_RETURN_IF_ERROR(check_output_file(path));
  std::string temp = path + ".tmp-XXXXXX";
  int raw_fd = -1;
  {
    RegistrationWindow window;
    raw_fd = ::mkostemp(temp.data(), O_CLOEXEC);
    if (raw_fd >= 0) register_temporary(temp);
  }
  FileDescriptor fd(raw_fd);
  if (fd.get() < 0) return io_error("cannot create a temporary file beside it: " + errno_text());
  auto remove_temp = [&] {
    ::unlink(temp.c_str());
    unregister_temporary(temp);
  };
  auto fail = [&](const std::string& what) {
    std::string message = what + ": " + errno_text();
    ::close(fd.release());
    remove_temp();
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
    std::string message = "close failed: " + errno_text();
    remove_temp();
    return io_error(message);
  }
  return temp;
}

Status rename_into_place(const std::string& temp, const std::string& path) {
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    std::string message = "cannot rename the temporary file into place: " + errno_text();
    ::unlink(temp.c_str());
    unregister_temporary(temp);
    return io_error(message);
  }
  unregister_temporary(temp);
  return Status::ok();
}

// Removes a staged temporary file that will not be committed.
void discard_temporary(const std::string& temp) {
  ::unlink(temp.c_str());
  unregister_temporary(temp);
}

}  // namespace

Status check_output_path(const std::string& path) {
  LODBAKE_RETURN_IF_ERROR(check_output_file(path));
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "."
                             : slash == 0               ? "/"
                                                        : path.substr(0, slash);
  // The same words as when creating the temporary file fails, which this
  // foresees.
  if (::faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    return io_error("cannot create a temporary file beside it: " + errno_text());
  return Status::ok();
}

void remove_temporaries_on_signals() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (int sig : kCleanupSignals) {
      struct sigaction old {};
      // A signal ignored from the start (nohup, a background job) stays
      // ignored.
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_reraise;
      action.sa_mask = cleanup_signal_set();  // one cleanup at a time
      action.sa_flags = SA_RESTART;
      ::sigaction(sig, &action, nullptr);
    }
  });
}

Status write_file_atomic(const std::string& path, const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(std::string temp, write_temporary_beside(path, data, size));
  return rename_into_place(temp, path);
}

StagedOutputs::~StagedOutputs() {
  for (const File& file : files_)
    discard_temporary(file.temp);
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
        discard_temporary(files[j].temp);
      if (failed_path != nullptr) *failed_path = files[i].path;
      return renamed;
    }
  }
  return Status::ok();
}

}  // namespace lodbake
