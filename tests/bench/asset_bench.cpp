// Whole assets in and out: lodbake's import (read_scene_file: parse, decode,
// images) and export against gltfpack's plain copy of the same asset (npm
// gltfpack, `gltfpack -i A -o B.glb -noq`), one row per asset, best of --runs.
// Export is timed three ways: write_scene_glb to memory; that plus a plain
// write of the .glb (no fsync, as gltfpack's CLI writes), which the total
// and the ratio use; and write_scene_file, the tools' atomic write (temporary
// file, fsync, rename).
//
// The allocator keeps freed memory (mallopt), as gltfpack's wasm heap does,
// so that the best run of both is a warm one: with glibc's defaults, whether
// a run of lodbake pays fresh page faults for its multi-megabyte buffers
// depends on the allocations before it (--default-malloc shows that).
//
// gltfpack is timed two ways: inside one node process through its library
// (tests/bench/gltfpack_copy.mjs: the wasm compiled once, only the pack
// calls timed, reading and writing files as the CLI does), and as the CLI a
// user runs, a whole `node cli.js ...` process each time, shown with and
// without node's start-up (`node -e ""`). Without node or the npm tools the
// lodbake columns are printed with a note.
//
//   bench_assets [--runs N] [--json] [--no-cli] [--default-malloc] [--node PATH] [--npm DIR]
//                ASSET...
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "formats/support/file_io.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_summary.h"

namespace {

namespace fs = std::filesystem;
using lodbake::bench::Clock;
using lodbake::bench::seconds_since;

struct LodbakeRow {
  std::string error;  // empty when the asset was read and written
  uint64_t triangles = 0;
  double import_ms = 0, export_memory_ms = 0, export_file_ms = 0, export_atomic_ms = 0;
  uint64_t output_bytes = 0;
};

struct GltfpackRow {
  std::string error;    // why there is no figure ("not run" when node is missing)
  double pack_ms = -1;  // in-process pack(), best of runs
  double cli_ms = -1;   // whole `node cli.js` process, best of runs
  uint64_t output_bytes = 0;
};

struct Row {
  std::string path;
  uint64_t input_bytes = 0;
  LodbakeRow lodbake;
  GltfpackRow gltfpack;
};

// The best wall milliseconds of `runs` calls of `body(run)`; -1 as soon as one fails.
template <typename Body>
double best_ms(int runs, Body body) {
  double best = 1e300;
  for (int i = 0; i < runs; ++i) {
    const Clock::time_point start = Clock::now();
    if (!body(i)) return -1;
    best = std::min(best, 1e3 * seconds_since(start));
  }
  return best;
}

uint64_t file_bytes(const fs::path& path) {
  std::error_code error;
  const uintmax_t size = fs::file_size(path, error);
  return error ? 0 : static_cast<uint64_t>(size);
}

// The asset's bytes on disk: the file plus the buffers and images its JSON
// names by relative URI (a .gltf's .bin and textures), each counted once.
uint64_t asset_input_bytes(const std::string& path) {
  auto bytes = lodbake::read_file(path);
  if (!bytes.is_ok()) return 0;
  const lodbake::Bytes& data = bytes.value();
  std::string text(data.begin(), data.end());
  // A GLB's JSON is its first chunk: 12-byte header, then length and type.
  if (text.size() >= 20 && text.compare(0, 4, "glTF") == 0) {
    const uint32_t length = static_cast<uint32_t>(data[12]) | static_cast<uint32_t>(data[13]) << 8 |
                            static_cast<uint32_t>(data[14]) << 16 |
                            static_cast<uint32_t>(data[15]) << 24;
    text = text.substr(20, std::min<size_t>(length, text.size() - 20));
  }
  uint64_t total = data.size();
  const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
  if (!root.is_object()) return total;
  std::vector<std::string> uris;
  for (const char* key : {"buffers", "images"}) {
    auto list = root.find(key);
    if (list == root.end() || !list->is_array()) continue;
    for (const nlohmann::json& item : *list) {
      auto uri = item.find("uri");
      if (uri != item.end() && uri->is_string() && uri->get<std::string>().rfind("data:", 0) != 0)
        uris.push_back(uri->get<std::string>());
    }
  }
  std::sort(uris.begin(), uris.end());
  uris.erase(std::unique(uris.begin(), uris.end()), uris.end());
  for (const std::string& uri : uris)
    total += file_bytes(fs::path(path).parent_path() / uri);
  return total;
}

// Outputs go to `out_prefix` + a suffix naming the run: every run writes a
// new file, as replacing one that was just written costs more on ext4
// (gltfpack's runs are set up alike).
LodbakeRow run_lodbake(const std::string& path, const std::string& out_prefix, int runs) {
  LodbakeRow row;
  std::optional<lodbake::Scene> scene;
  std::string error;
  row.import_ms = best_ms(runs, [&](int) {
    lodbake::ImportReport report;
    auto read = lodbake::read_scene_file(path, lodbake::SceneResources(), &report);
    if (!read.is_ok()) {
      error = "import: " + read.status().message();
      return false;
    }
    scene = std::move(read.value());
    return true;
  });
  if (row.import_ms < 0) {
    row.error = error;
    return row;
  }
  row.triangles = lodbake::summarize_scene(*scene).triangles;
  row.export_memory_ms = best_ms(runs, [&](int) {
    lodbake::SceneWriteReport report;
    auto glb = lodbake::write_scene_glb(*scene, &report);
    if (!glb.is_ok()) {
      error = "export: " + glb.status().message();
      return false;
    }
    row.output_bytes = glb.value().size();
    return true;
  });
  if (row.export_memory_ms < 0) {
    row.error = error;
    return row;
  }
  row.export_file_ms = best_ms(runs, [&](int run) {
    const std::string output = out_prefix + ".lodbake.r" + std::to_string(run) + ".glb";
    lodbake::SceneWriteReport report;
    auto glb = lodbake::write_scene_glb(*scene, &report);
    FILE* file = glb.is_ok() ? std::fopen(output.c_str(), "wb") : nullptr;
    if (!file) return false;
    const bool written =
        std::fwrite(glb.value().data(), 1, glb.value().size(), file) == glb.value().size();
    return std::fclose(file) == 0 && written;
  });
  row.export_atomic_ms = best_ms(runs, [&](int run) {
    const std::string output = out_prefix + ".atomic.r" + std::to_string(run) + ".glb";
    lodbake::SceneWriteReport report;
    lodbake::Status written = lodbake::write_scene_file(output, *scene, &report);
    if (!written.is_ok()) error = "export: " + written.message();
    return written.is_ok();
  });
  if (row.export_file_ms < 0) row.error = "export: cannot write a file in the scratch folder";
  if (row.export_atomic_ms < 0) row.error = error;
  return row;
}

struct NodeSetup {
  std::string node;    // the node program; empty when not found
  std::string npm;     // the folder with node_modules/gltfpack
  std::string script;  // gltfpack_copy.mjs
  std::string note;    // why gltfpack was not run, or empty
  double startup_ms = -1;
  double wasm_init_ms = -1;
};

// Runs gltfpack_copy.mjs once over every asset and fills each row's pack
// time and output size from its tab-separated lines.
void run_gltfpack_library(NodeSetup* setup, std::vector<Row>* rows, const fs::path& out_dir,
                          int runs) {
  std::string command = lodbake::bench::shell_quoted(setup->node) + " " +
                        lodbake::bench::shell_quoted(setup->script) + " --modules " +
                        lodbake::bench::shell_quoted(setup->npm) + " --out " +
                        lodbake::bench::shell_quoted(out_dir.string()) + " --runs " +
                        std::to_string(runs);
  for (const Row& row : *rows)
    command += " " + lodbake::bench::shell_quoted(row.path);
  command += " 2> " + lodbake::bench::shell_quoted((out_dir / "gltfpack_copy.log").string());
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) {
    setup->note = "could not start node";
    return;
  }
  std::map<std::string, std::vector<std::string>> lines;  // by file
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), pipe)) {
    std::string line(buffer);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, '\t');)
      fields.push_back(field);
    if (fields.size() == 2 && fields[0] == "init")
      setup->wasm_init_ms = std::atof(fields[1].c_str());
    if (fields.size() >= 3 && (fields[0] == "ok" || fields[0] == "failed"))
      lines[fields[1]] = fields;
  }
  const int status = ::pclose(pipe);
  if (status != 0 && lines.empty()) {
    setup->note = WIFEXITED(status) && WEXITSTATUS(status) == 77
                      ? "gltfpack is not installed in " + setup->npm + " (make npm-deps)"
                      : "gltfpack_copy.mjs failed (see its log)";
    return;
  }
  for (Row& row : *rows) {
    auto found = lines.find(row.path);
    if (found == lines.end()) {
      row.gltfpack.error = "no result";
    } else if (found->second[0] == "failed") {
      row.gltfpack.error = found->second[2];
    } else if (found->second.size() >= 4) {
      row.gltfpack.pack_ms = std::atof(found->second[2].c_str());
      row.gltfpack.output_bytes = std::strtoull(found->second[3].c_str(), nullptr, 10);
    }
  }
}

// The best wall milliseconds of `runs` runs of the command; -1 when it
// fails. `output`, the file it writes, is removed before each run (untimed).
double best_command_ms(const std::vector<std::string>& argv, const fs::path& output,
                       const fs::path& log, int runs) {
  double best = 1e300;
  for (int i = 0; i < runs; ++i) {
    std::error_code ignored;
    fs::remove(output, ignored);
    const lodbake::bench::ToolRun run = lodbake::bench::run_tool(argv, log.string());
    if (run.exit_status != 0) return -1;
    best = std::min(best, 1e3 * run.wall_seconds);
  }
  return best;
}

std::string name_of(const std::string& path) {
  return fs::path(path).filename().string();
}

std::string ms_text(double ms) {
  if (ms < 0) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", ms);
  return text;
}

double lodbake_total_ms(const LodbakeRow& row) {
  return row.import_ms + row.export_file_ms;
}

void print_table(const std::vector<Row>& rows, const NodeSetup& setup, bool cli, int runs) {
  std::printf("%-30s %7s %8s | %7s %7s %7s %7s %7s %8s | %7s %7s %8s %6s %8s\n", "asset", "tris",
              "in bytes", "import", "exp mem", "exp file", "exp atom", "total", "out bytes",
              "gp pack", "gp cli", "cli-node", "ratio", "gp bytes");
  for (const Row& row : rows) {
    const LodbakeRow& ours = row.lodbake;
    const GltfpackRow& peer = row.gltfpack;
    std::printf("%-30s ", name_of(row.path).c_str());
    if (!ours.error.empty()) {
      std::printf("lodbake failed: %s\n", ours.error.c_str());
      continue;
    }
    std::printf("%7llu %8llu | %7s %7s %7s %7s %7s %8llu | ",
                static_cast<unsigned long long>(ours.triangles),
                static_cast<unsigned long long>(row.input_bytes), ms_text(ours.import_ms).c_str(),
                ms_text(ours.export_memory_ms).c_str(), ms_text(ours.export_file_ms).c_str(),
                ms_text(ours.export_atomic_ms).c_str(), ms_text(lodbake_total_ms(ours)).c_str(),
                static_cast<unsigned long long>(ours.output_bytes));
    if (!setup.note.empty()) {
      std::printf("gltfpack not run\n");
      continue;
    }
    if (peer.pack_ms < 0) {
      std::printf("gltfpack failed: %s\n", peer.error.c_str());
      continue;
    }
    char ratio[32];
    std::snprintf(ratio, sizeof(ratio), "%.2fx", peer.pack_ms / lodbake_total_ms(ours));
    const double without_node =
        peer.cli_ms >= 0 && setup.startup_ms >= 0 ? peer.cli_ms - setup.startup_ms : -1;
    std::printf("%7s %7s %8s %6s %8llu\n", ms_text(peer.pack_ms).c_str(),
                ms_text(peer.cli_ms).c_str(), ms_text(without_node).c_str(), ratio,
                static_cast<unsigned long long>(peer.output_bytes));
  }
  std::printf(
      "milliseconds, best of %d; exp mem = GLB in memory; exp file = GLB written plainly (no "
      "fsync);\n"
      "exp atom = write_scene_file (temporary file, fsync, rename); total = import + exp file;\n"
      "gp pack = gltfpack's pack() in one node process (file in, .glb file out, wasm compiled "
      "once);\n"
      "gp cli = `node cli.js -i A -o B.glb -noq` as a process; cli-node = that minus node's "
      "start-up;\n"
      "ratio = gp pack / lodbake total (above 1: lodbake is faster)\n",
      runs);
  if (!setup.note.empty()) {
    std::printf("note: gltfpack not run: %s\n", setup.note.c_str());
  } else {
    std::printf("node start-up (node -e \"\"): %s ms; gltfpack wasm load and compile: %s ms%s\n",
                ms_text(setup.startup_ms).c_str(), ms_text(setup.wasm_init_ms).c_str(),
                cli ? "" : " (--no-cli: CLI not timed)");
  }
}

nlohmann::json ms_json(double ms) {
  return ms < 0 ? nlohmann::json() : nlohmann::json(ms);
}

void print_json(const std::vector<Row>& rows, const NodeSetup& setup, int runs) {
  nlohmann::json out;
  out["runs"] = runs;
  out["node_startup_ms"] = ms_json(setup.startup_ms);
  out["gltfpack_wasm_init_ms"] = ms_json(setup.wasm_init_ms);
  if (!setup.note.empty()) out["note"] = setup.note;
  out["assets"] = nlohmann::json::array();
  for (const Row& row : rows) {
    nlohmann::json asset;
    asset["asset"] = name_of(row.path);
    asset["path"] = row.path;
    asset["input_bytes"] = row.input_bytes;
    nlohmann::json ours;
    if (row.lodbake.error.empty()) {
      asset["triangles"] = row.lodbake.triangles;
      ours["import_ms"] = row.lodbake.import_ms;
      ours["export_memory_ms"] = row.lodbake.export_memory_ms;
      ours["export_file_ms"] = row.lodbake.export_file_ms;
      ours["export_atomic_ms"] = row.lodbake.export_atomic_ms;
      ours["total_ms"] = lodbake_total_ms(row.lodbake);
      ours["output_bytes"] = row.lodbake.output_bytes;
    } else {
      ours["error"] = row.lodbake.error;
    }
    asset["lodbake"] = ours;
    if (setup.note.empty()) {
      nlohmann::json peer;
      if (row.gltfpack.pack_ms >= 0) {
        peer["pack_ms"] = row.gltfpack.pack_ms;
        peer["cli_ms"] = ms_json(row.gltfpack.cli_ms);
        peer["cli_without_startup_ms"] = ms_json(row.gltfpack.cli_ms >= 0 && setup.startup_ms >= 0
                                                     ? row.gltfpack.cli_ms - setup.startup_ms
                                                     : -1);
        peer["output_bytes"] = row.gltfpack.output_bytes;
        if (row.lodbake.error.empty())
          asset["ratio"] = row.gltfpack.pack_ms / lodbake_total_ms(row.lodbake);
      } else {
        peer["error"] = row.gltfpack.error;
      }
      asset["gltfpack"] = peer;
    }
    out["assets"].push_back(asset);
  }
  std::printf("%s\n", out.dump(2).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  bool json = false, cli = true, keep_memory = true;
  NodeSetup setup;
  setup.node = LODBAKE_BENCH_NODE;
  setup.npm = LODBAKE_BENCH_NPM_DIR;
  setup.script = LODBAKE_BENCH_GLTFPACK_SCRIPT;
  std::vector<Row> rows;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--json") {
      json = true;
    } else if (arg == "--no-cli") {
      cli = false;
    } else if (arg == "--default-malloc") {
      keep_memory = false;
    } else if (arg == "--node" && i + 1 < argc) {
      setup.node = argv[++i];
    } else if (arg == "--npm" && i + 1 < argc) {
      setup.npm = argv[++i];
    } else if (arg.rfind("--", 0) == 0) {
      std::fprintf(stderr, "Error: unknown option %s\n", arg.c_str());
      return 1;
    } else {
      rows.push_back({arg, 0, {}, {}});
    }
  }
  if (rows.empty()) {
    std::fprintf(stderr,
                 "usage: bench_assets [--runs N] [--json] [--no-cli] [--default-malloc] "
                 "[--node PATH] [--npm DIR] ASSET...\n");
    return 1;
  }
  if (keep_memory) {
    // The largest fixed mmap threshold glibc accepts (32 MiB on 64-bit); the
    // buffers here are smaller, so they come from the heap, which is never
    // trimmed.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
  }
  std::error_code error;
  std::string scratch_name = (fs::temp_directory_path() / "bench_assets.XXXXXX").string();
  if (!::mkdtemp(scratch_name.data())) {
    std::fprintf(stderr, "Error: cannot create a scratch folder in %s\n",
                 fs::temp_directory_path().c_str());
    return 2;
  }
  const fs::path scratch = scratch_name;

  for (size_t i = 0; i < rows.size(); ++i) {
    // The index keeps Duck.glb's outputs apart from Duck.gltf's.
    const std::string prefix =
        (scratch / (std::to_string(i) + "-" + fs::path(rows[i].path).stem().string())).string();
    rows[i].input_bytes = asset_input_bytes(rows[i].path);
    rows[i].lodbake = run_lodbake(rows[i].path, prefix, runs);
  }

  const fs::path cli_js = fs::path(setup.npm) / "node_modules" / "gltfpack" / "cli.js";
  if (setup.node.empty() || !lodbake::bench::tool_installed(setup.node))
    setup.note = "node not found";
  else if (!fs::exists(cli_js))
    setup.note = "gltfpack is not installed in " + setup.npm + " (make npm-deps)";
  if (setup.note.empty()) run_gltfpack_library(&setup, &rows, scratch, runs);
  if (setup.note.empty() && cli) {
    setup.startup_ms =
        best_command_ms({setup.node, "-e", ""}, scratch / "none", scratch / "node.log", runs);
    for (Row& row : rows) {
      if (row.gltfpack.pack_ms < 0) continue;
      const fs::path output = scratch / "gltfpack-cli.glb";
      row.gltfpack.cli_ms = best_command_ms(
          {setup.node, cli_js.string(), "-i", row.path, "-o", output.string(), "-noq"}, output,
          scratch / "gltfpack.log", runs);
    }
  }

  if (json)
    print_json(rows, setup, runs);
  else
    print_table(rows, setup, cli, runs);
  fs::remove_all(scratch, error);
  return 0;
}
