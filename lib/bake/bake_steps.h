// One step of a bake plan (lib/bake/recipe.h) on one input, in memory: the
// same library calls, options and META as the tool the step stands for, so
// its files are byte for byte what that tool writes (pack: lodbake-pack;
// simplify: lodbake-simplify --pm; lods: lodbake-simplify --lods; hierarchy,
// fan: lodbake-hierarchy, lodbake-fan; package: lodbake-pack A.lbk B.lbk ...).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/bake/recipe.h"
#include "lib/ingest/load_mesh.h"

namespace lodbake {

struct StepResult {
  std::vector<std::pair<std::string, Bytes>> files;  // the plan's outputs, in its order
  std::vector<std::string> warnings;                 // one line each, as the tool warns
  nlohmann::json report = nlohmann::json::object();  // counts the tool reports
};

// The meshes one input's steps load. The input is parsed once and checked
// and repaired once per set of load options that can give another mesh;
// every step gets a copy: parsing, checking and repairing a large scan
// costs as much as some steps. Safe to use from steps running side by
// side; a failed load fails every step that asks for it, with its status.
class InputMeshes {
 public:
  Status load(const std::string& input, const Bytes& bytes, const LoadOptions& options,
              LoadedMesh* loaded);

 private:
  struct Entry {
    std::once_flag once;
    Status status = Status::ok();
    LoadedMesh loaded;
  };
  std::once_flag parsed_once_;
  Status parsed_status_ = Status::ok();
  LoadedMesh parsed_;  // as parsed, before any check
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<Entry>> entries_;  // by the options that matter
};

// Runs `step` on `input` (its content `bytes`; referenced buffers and
// images are read next to it). `earlier` holds the files of the input's
// earlier steps by step name (package merges them); `meshes` the input's
// loaded meshes. Deterministic; fails with the status the tool would print.
Result<StepResult> run_bake_step(const StepPlan& step, const std::string& input, const Bytes& bytes,
                                 const std::map<std::string, std::vector<Bytes>>& earlier,
                                 InputMeshes* meshes);

}  // namespace lodbake
