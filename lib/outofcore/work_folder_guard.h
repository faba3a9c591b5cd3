// Removes a one-shot out-of-core run's work folder however the run ends: on
// return (destructor) and on SIGINT, SIGTERM or SIGHUP, so that an
// interrupted run leaves no `.lodbake-work-PID` folder of block files
// behind.
#pragma once

#include <string>

namespace lodbake {

class WorkFolderGuard {
 public:
  /// Guards `work` (the folder need not exist yet): installs the signal
  /// handler, chained before the one already installed (formats/support
  /// file_io.h's removal of temporary files), which still ends the process
  /// by the same signal. One guard at a time.
  explicit WorkFolderGuard(const std::string& work);
  /// Restores the previous handlers and removes the work files
  /// (remove_work_files()).
  ~WorkFolderGuard();

  /// Stops guarding: the folder is left as it is (a usage error before
  /// anything was written, or a caller's own folder).
  void release() { released_ = true; }

  WorkFolderGuard(const WorkFolderGuard&) = delete;
  WorkFolderGuard& operator=(const WorkFolderGuard&) = delete;

 private:
  std::string work_;
  bool released_ = false;
};

}  // namespace lodbake
