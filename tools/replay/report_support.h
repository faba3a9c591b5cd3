// lodbake-replay's report pieces shared by its modes: the --plot lines, the
// median of the timings, and the parts every report repeats (the JSON
// preamble of an in-process, --connect or --serve report, the text heading
// and view lines), written once so that the modes' reports agree.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/replay/replay_request.h"

namespace lodbake::cli::replay {

/// The middle value (the mean of the two middle ones); 0 when empty.
double median(std::vector<double> v);

/// "elephant.lbk, mode dag, path scan": the charts' heading.
std::string plot_title(const Request& request);

/// The --plot files as paths, for the reports.
std::vector<std::string> plot_paths(const Request& request, const std::vector<std::string>& files);

/// "plots         DIR: a.svg, b.svg"; nothing when no file was written.
void print_plots(const Request& request, const std::vector<std::string>& files);

/// A camera-path report's opening on FILE: schema, input, mode, path,
/// frames, validated, viewport, tolerance and tolerance_pixels.
nlohmann::json camera_report(const Request& request, size_t frames);

/// A --connect report's opening: schema, connect, mode, path, frames,
/// validated and tolerance_pixels.
nlohmann::json connect_report(const Request& request, const std::string& address, size_t frames);

/// A --serve report: schema, input, mode, served, seconds, clients, total.
nlohmann::json served_report(const Request& request, const std::string& address, double seconds,
                             nlohmann::json clients, nlohmann::json total);

/// "replay        FILE: mode M, path P, N frames[, every frame validated]".
void print_replay_line(const Request& request, size_t frames);

/// "view          WxH, fov F deg, tolerance T px", no line end.
void print_view(const Request& request);

}  // namespace lodbake::cli::replay
