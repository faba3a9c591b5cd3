// Runs gnuplot as a child process (fork + exec, no shell, so no quoting of
// file names) in the plot folder, its stdout and stderr captured so that a
// failure is one line naming what gnuplot said.
#include "tools/replay/plots.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "formats/support/file_io.h"
#include "tools/replay/replay_plots_gp.h"

namespace lodbake::cli {
namespace {

// A gnuplot single-quoted string: a quote inside is written twice.
std::string gnuplot_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\n' || c == '\r') continue;
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

bool is_directory(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// gnuplot's exit status and everything it printed.
Status run_gnuplot(const std::string& dir, std::string* output) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::dup2(pipe_fds[1], STDOUT_FILENO);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    ::execlp("gnuplot", "gnuplot", "replay.gp", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    if (output->size() < 65536) output->append(buffer, static_cast<size_t>(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
    return runtime_error("cannot run gnuplot (install Debian's gnuplot-nox)");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string first = output->substr(0, output->find('\n'));
    while (!first.empty() && (first[0] == ' ' || first[0] == '\t'))
      first.erase(0, 1);
    return runtime_error("gnuplot failed" + (first.empty() ? std::string() : ": " + first));
  }
  return Status::ok();
}

}  // namespace

std::vector<std::string> plot_files(const std::string& mode, const std::string& lanes) {
  if (mode == "dag") {
    std::vector<std::string> files = {"traversal_time.svg"};
    if (lanes != "priority") files.push_back("accuracy.svg");
    files.push_back("fronts.svg");
    files.push_back("operations.svg");
    return files;
  }
  if (mode == "sets") return {"recovery_time.svg"};
  return {"adapt_time.svg", "fronts.svg", "operations.svg"};
}

Status check_plot_folder(const std::string& dir) {
  struct stat st;
  if (::stat(dir.c_str(), &st) == 0)
    return S_ISDIR(st.st_mode) ? Status::ok() : io_error("not a folder");
  const size_t slash = dir.find_last_of('/');
  const std::string parent = slash == std::string::npos ? "."
                             : slash == 0               ? "/"
                                                        : dir.substr(0, slash);
  if (::faccessat(AT_FDCWD, parent.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    return io_error(std::string("cannot create the plot folder: ") + std::strerror(errno));
  return Status::ok();
}

Status write_plots(const PlotRequest& request, std::vector<std::string>* written) {
  const std::string& dir = request.dir;
  bool made_dir = false;
  LODBAKE_RETURN_IF_ERROR(check_plot_folder(dir));
  if (!is_directory(dir)) {
    if (::mkdir(dir.c_str(), 0777) != 0) {
      return Status(ErrorKind::kIo,
                    std::string("cannot create the plot folder: ") + std::strerror(errno));
    }
    made_dir = true;
  }
  std::vector<std::string> files;
  auto undo = [&](Status status) {
    for (const std::string& f : files)
      ::unlink((dir + "/" + f).c_str());
    if (made_dir) ::rmdir(dir.c_str());
    return status;
  };
  const std::string script =
      "mode = " + gnuplot_string(request.mode) + "\nlanes = " + gnuplot_string(request.lanes) +
      "\ntitle = " + gnuplot_string(request.title) + "\n" + kReplayPlotsScript;
  for (const auto& [name, text] :
       {std::pair<std::string, const std::string*>{"frames.csv", &request.csv},
        {"replay.gp", &script}}) {
    Status status = write_file_atomic(dir + "/" + name, *text);
    if (!status.is_ok()) return undo(status);
    files.push_back(name);
  }
  const std::vector<std::string> charts = plot_files(request.mode, request.lanes);
  for (const std::string& chart : charts)
    files.push_back(chart);  // removed on failure, whichever gnuplot wrote
  std::string output;
  Status ran = run_gnuplot(dir, &output);
  if (!ran.is_ok()) return undo(ran);
  for (const std::string& chart : charts) {
    struct stat st;
    if (::stat((dir + "/" + chart).c_str(), &st) != 0 || st.st_size == 0)
      return undo(runtime_error("gnuplot did not write " + chart));
  }
  *written = files;
  return Status::ok();
}

}  // namespace lodbake::cli
