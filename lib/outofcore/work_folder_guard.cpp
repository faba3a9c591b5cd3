// The handler cannot list a folder or format with snprintf (neither is
// async-signal-safe), so it builds every name the stages can write
// (block_NNNN.in/.out/.tris for the kMaxBlocks blocks a plan may hold, and
// plan.json) by hand in a buffer prepared before the signal, unlinks them,
// lets the chained handler unlink the temporary files of write_file_atomic()
// (its raise() stays pending until this handler returns) and removes the
// folder. A block file another thread creates meanwhile would keep the
// folder: the sweep runs again after a pause before giving up.
#include "lib/outofcore/work_folder_guard.h"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

#include "lib/outofcore/out_of_core.h"

namespace lodbake {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr size_t kPathBytes = 4096;

// The guarded folder with a trailing '/', and room for a file name after it.
char folder[kPathBytes];
size_t folder_length = 0;
std::atomic<bool> armed{false};
struct sigaction previous[3];

// Writes `name` after the folder and unlinks it.
void unlink_in_folder(const char* name, size_t length) {
  if (folder_length + length + 1 > kPathBytes) return;
  std::memcpy(folder + folder_length, name, length);
  folder[folder_length + length] = '\0';
  ::unlink(folder);
}

void sweep() {
  static const char kPlan[] = "plan.json";
  unlink_in_folder(kPlan, sizeof(kPlan) - 1);
  static const char* const kExtensions[] = {".in", ".out", ".tris"};
  char name[32] = "block_";
  for (uint32_t b = 0; b < kMaxBlocks; ++b) {
    // block_%04u, as out_of_core.cpp's numbered() (kMaxBlocks < 10000).
    name[6] = static_cast<char>('0' + b / 1000 % 10);
    name[7] = static_cast<char>('0' + b / 100 % 10);
    name[8] = static_cast<char>('0' + b / 10 % 10);
    name[9] = static_cast<char>('0' + b % 10);
    for (const char* ext : kExtensions) {
      const size_t n = std::strlen(ext);
      std::memcpy(name + 10, ext, n);
      unlink_in_folder(name, 10 + n);
    }
  }
}

void remove_folder_and_chain(int sig) {
  if (armed.exchange(false)) {
    sweep();
    size_t index = 0;
    while (kSignals[index] != sig)
      ++index;
    // The chained handler unlinks the temporary files and re-raises (held
    // until this handler returns); without one, do the re-raise here.
    const struct sigaction& before = previous[index];
    if (!(before.sa_flags & SA_SIGINFO) && before.sa_handler != SIG_DFL &&
        before.sa_handler != SIG_IGN) {
      before.sa_handler(sig);
    } else {
      ::signal(sig, SIG_DFL);
      ::raise(sig);
    }
    folder[folder_length - 1] = '\0';
    for (int attempt = 0; attempt < 3 && ::rmdir(folder) != 0; ++attempt) {
      struct timespec pause {
        0, 20000000
      };
      ::nanosleep(&pause, nullptr);
      folder[folder_length - 1] = '/';
      sweep();
      folder[folder_length - 1] = '\0';
    }
    return;
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

WorkFolderGuard::WorkFolderGuard(const std::string& work) : work_(work) {
  // A path too long for the buffer is still removed on return, not on a
  // signal.
  if (work.size() + 32 >= kPathBytes) return;
  std::memcpy(folder, work.data(), work.size());
  folder[work.size()] = '/';
  folder_length = work.size() + 1;
  struct sigaction action {};
  action.sa_handler = remove_folder_and_chain;
  sigemptyset(&action.sa_mask);
  for (int sig : kSignals)
    sigaddset(&action.sa_mask, sig);  // one cleanup at a time
  action.sa_flags = SA_RESTART;
  for (size_t i = 0; i < 3; ++i) {
    // A signal ignored from the start (nohup) stays ignored.
    if (::sigaction(kSignals[i], nullptr, &previous[i]) != 0 || previous[i].sa_handler == SIG_IGN) {
      previous[i].sa_handler = SIG_IGN;
      continue;
    }
    ::sigaction(kSignals[i], &action, nullptr);
  }
  armed.store(true);
}

WorkFolderGuard::~WorkFolderGuard() {
  if (folder_length != 0 && armed.exchange(false)) {
    for (size_t i = 0; i < 3; ++i)
      if (previous[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &previous[i], nullptr);
  }
  if (!released_) remove_work_files(work_);
}

}  // namespace lodbake
