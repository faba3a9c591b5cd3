// lodbake-replay's mode sets: BASE + VSPL + SETS from lodbake-strips, the
// strip paper's LoD-recovery tests (lib/replay/sets_replay.h). Not
// camera-driven: one step per LoD recovered, each test from LoD 0 to the
// coarsest and back; its report (--csv, --plot, JSON or text) is a row per
// (spacing, percent).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "formats/sections/open_container.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/structure_loading.h"
#include "tools/replay/plots.h"
#include "tools/replay/replay_request.h"
#include "tools/replay/report_support.h"

namespace lodbake::cli::replay {
namespace {

Result<SetsStructure> load_sets(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(OpenedContainer file, open_container(bytes));
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kSets));
  return load_sets_structure(file.decoded(), group);
}

std::string percent_text(double percent) {
  std::ostringstream out;
  out << percent;
  return out.str();
}

}  // namespace

// The recovery tests: every (spacing, percent), linear first, each from LoD
// 0 to the coarsest LoD and back.
int run_sets(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<SetsStructure> loaded = load_sets(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const ProgressiveMesh& pm = *loaded.value().pm;
  const SetsGraph& graph = *loaded.value().graph;
  // An asset's strips (WEDG beside the VSPL): every recovered LoD's
  // corners have their wedges, which --validate checks.
  const SetsStructure& structure = loaded.value();
  const CornerWedges* lookup = structure.lookup ? &*structure.lookup : nullptr;
  Result<SetsReplay> created = SetsReplay::create(pm, graph, lookup, structure.wedges.get());
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  SetsReplay& replay = created.value();

  std::vector<LodSpacing> spacings;
  if (request.spacing != "exponential") spacings.push_back(LodSpacing::kLinear);
  if (request.spacing != "linear") spacings.push_back(LodSpacing::kExponential);
  std::vector<SetsTestSummary> summaries;
  std::ostringstream csv;
  csv << "spacing,percent,step,lod,strips,indices,triangles,fresh_us,coherent_us\n";
  size_t recovered = 0;
  Progress progress(tool, "recovering");
  const size_t tests = spacings.size() * request.percents.size();
  for (LodSpacing spacing : spacings) {
    for (double percent : request.percents) {
      const std::vector<uint32_t> lods = recovery_test_lods(replay.lod_count(), percent, spacing);
      Result<std::vector<SetsStep>> steps = run_sets_test(&replay, lods, request.validate);
      if (!steps.is_ok()) {
        return tool.fail(request.input,
                         Status(steps.status().kind(), std::string(spacing_name(spacing)) + " " +
                                                           percent_text(percent) + "%, " +
                                                           steps.status().message()));
      }
      summaries.push_back(summarize_sets_test(spacing, percent, steps.value()));
      recovered += steps.value().size();
      if (!request.csv.empty() || !request.plot.empty()) {
        for (size_t k = 0; k < steps.value().size(); ++k) {
          const SetsStep& step = steps.value()[k];
          csv << spacing_name(spacing) << ',' << percent << ',' << k << ',' << step.lod << ','
              << step.strips << ',' << step.indices << ',' << step.triangles << ',' << step.fresh_us
              << ',' << step.coherent_us << '\n';
        }
      }
      progress.update(static_cast<double>(summaries.size()) / tests);
    }
  }
  std::vector<std::string> plots;
  if (!request.plot.empty()) {
    const Status plotted =
        write_plots({request.plot, request.mode, "", plot_title(request), csv.str()}, &plots);
    if (!plotted.is_ok()) return tool.fail(request.plot, plotted);
  }
  if (!request.csv.empty()) {
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  if (tool.json()) {
    nlohmann::json rows = nlohmann::json::array();
    for (const SetsTestSummary& t : summaries) {
      rows.push_back({{"spacing", spacing_name(t.spacing)},
                      {"percent", t.percent},
                      {"lods", t.lods},
                      {"indices", t.indices},
                      {"fresh_us_per_lod", t.fresh_us_per_lod},
                      {"coherent_us_per_lod", t.coherent_us_per_lod},
                      {"fresh_mindices_per_s", t.fresh_mindices_per_s},
                      {"coherent_mindices_per_s", t.coherent_mindices_per_s}});
    }
    nlohmann::json sets = {{"strips", graph.strip_count()},
                           {"nodes", graph.node_count()},
                           {"lods", graph.lod_count},
                           {"base_triangles", pm.base.triangle_count()}};
    if (replay.has_wedges()) {
      sets["wedges"] = structure.wedges->wedge_count();
      if (request.validate) sets["checked_corners"] = replay.checked_corners();
    }
    nlohmann::json report = {{"schema", kReplaySchema},
                             {"input", request.input},
                             {"mode", request.mode},
                             {"validated", request.validate},
                             {"sets", sets},
                             {"spacing", request.spacing},
                             {"percents", request.percents},
                             {"lods_recovered", recovered},
                             {"timing", "steady_clock, recovery alone"},
                             {"tests", rows}};
    if (!plots.empty()) report["plots"] = plot_paths(request, plots);
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode sets, " << summaries.size()
            << " recovery tests, " << recovered << " LoDs recovered"
            << (request.validate ? ", every LoD validated" : "") << "\n";
  std::cout << "sets          " << graph.strip_count() << " strips, " << graph.node_count()
            << " nodes over " << graph.lod_count << " LoDs, " << pm.base.triangle_count()
            << " base triangles";
  if (replay.has_wedges()) {
    std::cout << ", " << structure.wedges->wedge_count() << " wedges";
    if (request.validate)
      std::cout << " (every recovered corner's checked: " << replay.checked_corners() << ")";
  }
  std::cout << "\n";
  print_plots(request, plots);
  std::cout
      << "tests         LoD 0 to the coarsest and back; recovery alone (steady_clock): fresh\n"
         "              recover() and coherent recover_coherent() at every LoD\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%-12s %7s %7s %14s %17s %15s %18s\n", "spacing", "percent",
                "LoDs", "fresh us/LoD", "coherent us/LoD", "fresh M idx/s", "coherent M idx/s");
  std::cout << line;
  for (const SetsTestSummary& t : summaries) {
    std::snprintf(line, sizeof line, "%-12s %6s%% %7zu %14.1f %17.1f %15.1f %18.1f\n",
                  spacing_name(t.spacing), percent_text(t.percent).c_str(), t.lods,
                  t.fresh_us_per_lod, t.coherent_us_per_lod, t.fresh_mindices_per_s,
                  t.coherent_mindices_per_s);
    std::cout << line;
  }
  return 0;
}

}  // namespace lodbake::cli::replay
