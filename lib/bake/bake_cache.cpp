#include "lib/bake/bake_cache.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "formats/support/version.h"
#include "lib/core/sha256.h"
#include "lib/ingest/meta_input.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace {

// Bumped when a cached entry's layout or the key's contents change.
constexpr int kCacheFormat = 1;

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

nlohmann::json input_fingerprint(const std::string& input, const Bytes& bytes) {
  const size_t slash = input.find_last_of('/');
  nlohmann::json print = {
      {"name", to_valid_utf8(slash == std::string::npos ? input : input.substr(slash + 1))},
      {"sha256", sha256_hex(bytes.data(), bytes.size())}};
  std::vector<std::pair<std::string, nlohmann::json>> resources;
  if (is_asset(input, bytes) || is_scene_source(input, bytes)) {
    SceneResources recorder;
    const std::string folder = folder_of(input) + "/";
    recorder.on_read = [&](const std::string& path, const Bytes* content) {
      const std::string relative =
          path.compare(0, folder.size(), folder) == 0 ? path.substr(folder.size()) : path;
      resources.emplace_back(relative, content == nullptr ? nlohmann::json(nullptr)
                                                          : nlohmann::json(sha256_hex(
                                                                content->data(), content->size())));
    };
    // Read only for what it references; a reader's failure is the step's
    // to report, and the files read until then are in the key.
    ImportReport report;
    (void)read_scene_bytes(input, bytes, recorder, &report);
  }
  std::sort(resources.begin(), resources.end());
  resources.erase(std::unique(resources.begin(), resources.end()), resources.end());
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [path, sha] : resources)
    list.push_back({path, sha});
  print["resources"] = list;
  return print;
}

std::vector<std::string> referenced_files(const std::string& input,
                                          const nlohmann::json& fingerprint) {
  std::vector<std::string> files;
  for (const nlohmann::json& resource : fingerprint["resources"]) {
    if (resource[1].is_null()) continue;  // missing: nothing to watch yet
    const std::string path = resource[0].get<std::string>();
    files.push_back(path.empty() || path[0] == '/' ? path : folder_of(input) + "/" + path);
  }
  return files;
}

std::string step_key(const nlohmann::json& fingerprint, const StepPlan& step,
                     const std::vector<std::string>& merged) {
  // The output names' extensions choose writers (lods), so they count; the
  // folders they go to do not.
  nlohmann::json extensions = nlohmann::json::array();
  for (const std::string& out : step.outputs) {
    const size_t dot = out.find_last_of('.');
    const size_t slash = out.find_last_of('/');
    extensions.push_back(dot == std::string::npos || (slash != std::string::npos && dot < slash)
                             ? ""
                             : out.substr(dot + 1));
  }
  const nlohmann::json key = {{"cache_format", kCacheFormat},
                              {"lodbake", kLodbakeVersion},
                              {"step", step.step},
                              {"options", step.options},
                              {"input", fingerprint},
                              {"outputs", extensions},
                              {"merged", merged}};
  const std::string text = key.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return sha256_hex(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

std::string BakeCache::entry(const std::string& key) const {
  return folder_ + "/" + key.substr(0, 2) + "/" + key;
}

std::optional<StepResult> BakeCache::load(const std::string& key, const StepPlan& step) const {
  const std::string dir = entry(key);
  Result<Bytes> meta = read_file(dir + "/step.json");
  if (!meta.is_ok()) return std::nullopt;
  const nlohmann::json info =
      nlohmann::json::parse(meta.value().begin(), meta.value().end(), nullptr, false);
  if (info.is_discarded() || !info.is_object() ||
      info.value("files", size_t{0}) != step.outputs.size())
    return std::nullopt;
  StepResult out;
  for (size_t i = 0; i < step.outputs.size(); ++i) {
    Result<Bytes> file = read_file(dir + "/" + std::to_string(i));
    if (!file.is_ok()) return std::nullopt;
    out.files.emplace_back(step.outputs[i], std::move(file).value());
  }
  out.warnings = info.value("warnings", std::vector<std::string>{});
  out.report = info.value("report", nlohmann::json::object());
  return out;
}

Status BakeCache::store(const std::string& key, const StepResult& result) const {
  const std::string dir = entry(key);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) return Status(ErrorKind::kIo, dir + ": cannot create the folder: " + error.message());
  for (size_t i = 0; i < result.files.size(); ++i)
    LODBAKE_RETURN_IF_ERROR(
        write_file_atomic(dir + "/" + std::to_string(i), result.files[i].second));
  const nlohmann::json info = {
      {"files", result.files.size()}, {"warnings", result.warnings}, {"report", result.report}};
  return write_file_atomic(dir + "/step.json",
                           info.dump(1, ' ', false, nlohmann::json::error_handler_t::replace));
}

std::string default_bake_cache_folder() {
  if (const char* dir = std::getenv("LODBAKE_CACHE_DIR"); dir != nullptr && *dir != '\0')
    return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg == '/')
    return std::string(xdg) + "/lodbake";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home == '/')
    return std::string(home) + "/.cache/lodbake";
  return ".lodbake-cache";
}

}  // namespace lodbake
