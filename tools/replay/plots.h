// lodbake-replay --plot DIR: the paper-style charts of a run, drawn by
// gnuplot (Debian's gnuplot-nox) from the run's per-frame rows with the
// script tools/replay/replay_plots.gp, which is compiled in and written next
// to the data so that a user can edit and re-run it.
#pragma once

#include <string>
#include <vector>

#include "formats/support/status.h"

namespace lodbake::cli {

struct PlotRequest {
  std::string dir;    ///< created when missing (its parent must exist)
  std::string mode;   ///< vhier, dag, fan or sets
  std::string lanes;  ///< dag: the traversals replayed, space-separated
  std::string title;  ///< shown above every chart
  std::string csv;    ///< the rows --csv writes, header first
};

/// The charts a mode draws, as file names in the folder.
std::vector<std::string> plot_files(const std::string& mode, const std::string& lanes);

/// Checks, before the run, that DIR is a folder or can be made: kIo "not a
/// folder" when something else is there (a file, a device such as
/// /dev/full), "cannot create the plot folder: ..." when its parent is
/// missing or not writable.
Status check_plot_folder(const std::string& dir);

/// Writes DIR/frames.csv and DIR/replay.gp and runs gnuplot in DIR; on
/// success `*written` lists every file written (the data, the script and
/// the SVG charts). On failure nothing it wrote is left behind.
/// \return kIo when DIR cannot be made or written, kRuntime when gnuplot
///   cannot be run, fails or leaves a chart out.
Status write_plots(const PlotRequest& request, std::vector<std::string>* written);

}  // namespace lodbake::cli
