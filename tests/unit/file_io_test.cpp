// formats/support/file_io: outputs that cannot be written (devices, missing
// folders), write errors part-way (a file size limit standing in for a full
// disk), and the temporary files of writes in progress removed when the
// process gets SIGINT, SIGTERM or SIGHUP. The signal tests fork a child that
// writes through the library and is killed by the parent.
#include "formats/support/file_io.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace lodbake {
namespace {

// A fresh empty folder for one test.
std::string make_folder() {
  std::string folder = ::testing::TempDir() + "lodbake_file_io_XXXXXX";
  EXPECT_NE(::mkdtemp(folder.data()), nullptr);
  return folder;
}

// The names in `folder`, sorted.
std::vector<std::string> folder_names(const std::string& folder) {
  std::vector<std::string> names;
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return names;
  while (const dirent* entry = ::readdir(dir)) {
    std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  ::closedir(dir);
  std::sort(names.begin(), names.end());
  return names;
}

bool has_temporary(const std::string& folder) {
  for (const std::string& name : folder_names(folder)) {
    if (name.find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

bool exists(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

// Waits up to 20 s for `pid` to end; kills it and fails when it does not.
int wait_for(pid_t pid) {
  int status = 0;
  for (int i = 0; i < 2000; ++i) {
    pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    struct timespec ten_ms {
      0, 10000000
    };
    ::nanosleep(&ten_ms, nullptr);
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  ADD_FAILURE() << "the child did not end";
  return status;
}

// In a child: the three signals with their default action and unblocked (the
// test may run where SIGINT is ignored, as background jobs are), then the
// cleanup handlers installed as every tool does at start-up.
void child_start() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    ::signal(sig, SIG_DFL);
    sigaddset(&set, sig);
  }
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  remove_temporaries_on_signals();
}

TEST(FileIo, DevicesAndMissingFoldersAreNotOutputs) {
  Status s = check_output_path("/dev/full");
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
  EXPECT_EQ(s.message(), "not a regular file; outputs replace regular files only");
  s = write_file_atomic("/dev/full", std::string("x"));
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
  EXPECT_EQ(s.message(), "not a regular file; outputs replace regular files only");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));  // still the device

  s = check_output_path("/nonexistent/lodbake/out.obj");
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
  EXPECT_EQ(s.message(), "cannot create a temporary file beside it: No such file or directory");
  // The same words when the write itself finds the folder missing.
  s = write_file_atomic("/nonexistent/lodbake/out.obj", std::string("x"));
  EXPECT_EQ(s.message(), "cannot create a temporary file beside it: No such file or directory");

  const std::string folder = make_folder();
  EXPECT_EQ(check_output_path(folder).message(), "is a directory");
  EXPECT_TRUE(check_output_path(folder + "/new.obj").is_ok());
  ASSERT_TRUE(write_file_atomic(folder + "/old.obj", std::string("x")).is_ok());
  EXPECT_TRUE(check_output_path(folder + "/old.obj").is_ok());
  const std::string cwd_relative = "lodbake_file_io_relative.obj";  // folder "."
  EXPECT_TRUE(check_output_path(cwd_relative).is_ok()) << check_output_path(cwd_relative).message();
  EXPECT_EQ(check_output_path("/dev/null/x.obj").kind(), ErrorKind::kIo);
}

// A write that fails part-way (here the file size limit, EFBIG; a full disk
// gives ENOSPC on the same path) is kIo and leaves neither the output nor
// the temporary file; an existing output keeps its bytes.
TEST(FileIo, AWriteErrorPartWayLeavesNoTemporaryFile) {
  const std::string folder = make_folder();
  const std::string kept = folder + "/kept.lbk";
  ASSERT_TRUE(write_file_atomic(kept, std::string("old")).is_ok());
  for (bool staged : {false, true}) {
    SCOPED_TRACE(staged ? "StagedOutputs" : "write_file_atomic");
    for (const std::string& out : {folder + "/new.lbk", kept}) {
      pid_t pid = ::fork();
      ASSERT_GE(pid, 0);
      if (pid == 0) {
        ::signal(SIGXFSZ, SIG_IGN);  // write() fails with EFBIG instead
        struct rlimit limit {
          4096, 4096
        };
        ::setrlimit(RLIMIT_FSIZE, &limit);
        const Bytes data(1 << 20, 7);
        Status s;
        if (staged) {
          StagedOutputs outputs;
          s = outputs.stage(out, data);
          if (s.is_ok()) s = outputs.commit();
        } else {
          s = write_file_atomic(out, data);
        }
        const bool words = s.message() == "write failed: File too large";
        ::_exit(s.kind() == ErrorKind::kIo && words ? 0 : 10);
      }
      const int status = wait_for(pid);
      ASSERT_TRUE(WIFEXITED(status));
      EXPECT_EQ(WEXITSTATUS(status), 0) << "not kIo \"write failed: File too large\"";
      EXPECT_FALSE(has_temporary(folder));
    }
    EXPECT_FALSE(exists(folder + "/new.lbk"));
    Result<Bytes> back = read_file(kept);
    ASSERT_TRUE(back.is_ok());
    EXPECT_EQ(std::string(back.value().begin(), back.value().end()), "old");
  }
}

// A child stages two outputs (their temporary files exist), tells the parent
// and waits; the parent sends `sig`. The child must die of `sig` and leave
// neither temporary file nor output.
void expect_staged_temporaries_removed_on(int sig) {
  const std::string folder = make_folder();
  int ready[2], never[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(never), 0);
  pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    child_start();
    ::close(ready[0]);
    ::close(never[1]);
    StagedOutputs outputs;
    const Bytes data(1 << 20, 1);
    if (!outputs.stage(folder + "/a.obj", data).is_ok() ||
        !outputs.stage(folder + "/b.lbk", data).is_ok())
      ::_exit(10);
    char byte = 1;
    if (::write(ready[1], &byte, 1) != 1) ::_exit(11);
    // Blocks before the commit until killed (or the parent goes away).
    while (::read(never[0], &byte, 1) < 0) {
    }
    ::_exit(12);
  }
  ::close(ready[1]);
  ::close(never[0]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the child could not stage its outputs";
  EXPECT_EQ(folder_names(folder).size(), 2u);
  EXPECT_TRUE(has_temporary(folder));
  ASSERT_EQ(::kill(pid, sig), 0);
  const int status = wait_for(pid);
  ::close(ready[0]);
  ::close(never[1]);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
  EXPECT_EQ(WTERMSIG(status), sig);
  EXPECT_EQ(folder_names(folder), std::vector<std::string>{});
}

TEST(FileIo, TemporariesAreRemovedOnSigterm) {
  expect_staged_temporaries_removed_on(SIGTERM);
}

TEST(FileIo, TemporariesAreRemovedOnSigint) {
  expect_staged_temporaries_removed_on(SIGINT);
}

TEST(FileIo, TemporariesAreRemovedOnSighup) {
  expect_staged_temporaries_removed_on(SIGHUP);
}

// A child rewrites one output in a loop with write_file_atomic(); killed at
// any moment (creating the temporary file, writing, flushing, renaming), it
// leaves the output whole or absent and never a temporary file.
TEST(FileIo, KilledAtAnyMomentOfAWriteLeavesNoTemporaryFile) {
  const std::string folder = make_folder();
  const std::string out = folder + "/out.lbk";
  const Bytes data(4 << 20, 3);
  for (long delay_us : {0L, 200L, 1000L, 3000L, 7000L, 15000L, 31000L, 63000L}) {
    SCOPED_TRACE(delay_us);
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      child_start();
      ::close(ready[0]);
      char byte = 1;
      if (::write(ready[1], &byte, 1) != 1) ::_exit(11);
      for (;;) {
        if (!write_file_atomic(out, data).is_ok()) ::_exit(10);
      }
    }
    ::close(ready[1]);
    char byte = 0;
    ASSERT_EQ(::read(ready[0], &byte, 1), 1);
    ::close(ready[0]);
    struct timespec wait {
      0, delay_us * 1000
    };
    ::nanosleep(&wait, nullptr);
    ASSERT_EQ(::kill(pid, SIGTERM), 0);
    const int status = wait_for(pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_FALSE(has_temporary(folder));
    if (exists(out)) {
      Result<Bytes> back = read_file(out);
      ASSERT_TRUE(back.is_ok());
      EXPECT_EQ(back.value(), data);
    }
  }
}

// A signal that was ignored when the handlers were installed (nohup) stays
// ignored: the write goes on and completes.
TEST(FileIo, AnIgnoredSignalStaysIgnored) {
  const std::string folder = make_folder();
  int ready[2], go[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(go), 0);
  pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGHUP, SIG_IGN);
    remove_temporaries_on_signals();
    ::close(ready[0]);
    ::close(go[1]);
    StagedOutputs outputs;
    if (!outputs.stage(folder + "/a.obj", Bytes{1, 2}).is_ok()) ::_exit(10);
    char byte = 1;
    if (::write(ready[1], &byte, 1) != 1) ::_exit(11);
    if (::read(go[0], &byte, 1) != 1) ::_exit(12);
    ::_exit(outputs.commit().is_ok() ? 0 : 13);
  }
  ::close(ready[1]);
  ::close(go[0]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1);
  ASSERT_EQ(::kill(pid, SIGHUP), 0);
  ASSERT_EQ(::write(go[1], &byte, 1), 1);
  const int status = wait_for(pid);
  ::close(ready[0]);
  ::close(go[1]);
  ASSERT_TRUE(WIFEXITED(status)) << "exit status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(folder_names(folder), std::vector<std::string>{"a.obj"});
}

}  // namespace
}  // namespace lodbake
