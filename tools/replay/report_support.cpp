// lodbake-replay's shared report pieces (report_support.h): one definition
// of what the modes' reports have in common.
#include "tools/replay/report_support.h"

#include <algorithm>
#include <iostream>

namespace lodbake::cli::replay {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string plot_title(const Request& request) {
  const size_t slash = request.input.find_last_of('/');
  std::string title = slash == std::string::npos ? request.input : request.input.substr(slash + 1);
  title += ", mode " + request.mode;
  if (request.mode != "sets") {
    const size_t path_slash = request.path.find_last_of('/');
    title += ", path " +
             (path_slash == std::string::npos ? request.path : request.path.substr(path_slash + 1));
  }
  return title;
}

std::vector<std::string> plot_paths(const Request& request, const std::vector<std::string>& files) {
  std::vector<std::string> paths;
  for (const std::string& f : files)
    paths.push_back(request.plot + "/" + f);
  return paths;
}

void print_plots(const Request& request, const std::vector<std::string>& files) {
  if (files.empty()) return;
  std::cout << "plots         " << request.plot << ":";
  for (size_t i = 0; i < files.size(); ++i)
    std::cout << (i == 0 ? " " : ", ") << files[i];
  std::cout << "\n";
}

nlohmann::json camera_report(const Request& request, size_t frames) {
  return {{"schema", kReplaySchema},
          {"input", request.input},
          {"mode", request.mode},
          {"path", request.path},
          {"frames", frames},
          {"validated", request.validate},
          {"viewport",
           {{"width", request.options.viewport.width},
            {"height", request.options.viewport.height},
            {"fov_degrees", request.fov_degrees},
            {"near_fraction", request.options.viewport.near_fraction}}},
          {"tolerance", request.tolerance},
          {"tolerance_pixels", request.options.tolerance_pixels}};
}

nlohmann::json connect_report(const Request& request, const std::string& address, size_t frames) {
  return {{"schema", kReplaySchema},
          {"connect", address},
          {"mode", request.mode},
          {"path", request.path},
          {"frames", frames},
          {"validated", request.validate},
          {"tolerance_pixels", request.options.tolerance_pixels}};
}

nlohmann::json served_report(const Request& request, const std::string& address, double seconds,
                             nlohmann::json clients, nlohmann::json total) {
  return {{"schema", kReplaySchema},  {"input", request.input}, {"mode", request.mode},
          {"served", address},        {"seconds", seconds},     {"clients", std::move(clients)},
          {"total", std::move(total)}};
}

void print_replay_line(const Request& request, size_t frames) {
  std::cout << "replay        " << request.input << ": mode " << request.mode << ", path "
            << request.path << ", " << frames << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
}

void print_view(const Request& request) {
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px";
}

}  // namespace lodbake::cli::replay
