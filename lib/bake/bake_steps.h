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
#include "lib/simplify/simplify.h"

namespace lodbake {

struct StepResult {
  std::vector<std::pair<std::string, Bytes>> files;  // the plan's outputs, in its order
  std::vector<std::string> warnings;                 // one line each, as the tool warns
  nlohmann::json report = nlohmann::json::object();  // counts the tool reports
};

// The meshes one input's steps load. The input is parsed once and checked
// and repaired once per set of load options that can give another mesh,
// and the steps share that mesh: parsing, checking and repairing a large
// scan costs as much as some steps, and each copy 24 bytes per triangle. A
// simplification of such a mesh is run once for every step asking with the
// same options (the simplify step's progressive mesh is the strips step's
// on a default recipe). Safe to use from steps running side by side; a
// failed load or simplification fails every step that asks for it, with
// its status.
class InputMeshes {
 public:
  InputMeshes() = default;
  // `steps`: the steps that will ask, each loading once. The parse is
  // released once every step has loaded, a simplification once the last
  // step that needs it has taken it (without `steps`, both are kept).
  explicit InputMeshes(const std::vector<StepPlan>& steps);

  Result<std::shared_ptr<const LoadedMesh>> load(const std::string& input, const Bytes& bytes,
                                                 const LoadOptions& options);

  // simplify(mesh, options), `mesh` being what load() gave for
  // `load_options`: the same result as a run of its own, byte for byte.
  Result<std::shared_ptr<const SimplifyResult>> simplified(const TriangleMesh& mesh,
                                                           const LoadOptions& load_options,
                                                           const SimplifyOptions& options);

 private:
  struct Entry {
    std::once_flag once;
    Status status = Status::ok();
    std::shared_ptr<const LoadedMesh> loaded;
  };
  struct Simplification {
    std::once_flag once;
    Status status = Status::ok();
    std::shared_ptr<const SimplifyResult> result;
    size_t askers = 0;  // steps still to take it; 0: unknown, kept
  };
  Result<std::shared_ptr<const LoadedMesh>> parse(const std::string& input, const Bytes& bytes);

  std::mutex parse_mutex_;
  Status parsed_status_ = Status::ok();
  std::shared_ptr<const LoadedMesh> parsed_;  // as parsed, before any check; null once released
  bool per_corner_ = false;                   // the parse has per-corner attributes
  std::mutex mutex_;
  size_t loads_left_ = 0;  // before the parse is released; 0: unknown, kept
  std::map<std::string, std::unique_ptr<Entry>> entries_;  // by the options that matter
  std::map<std::string, std::unique_ptr<Simplification>> simplifications_;  // simplify_key()
};

// Runs `step` on `input` (its content `bytes`; referenced buffers and
// images are read next to it). `earlier` holds the files of the input's
// earlier steps by step name (package merges them and takes them: it may
// be null for the other steps); `meshes` the input's loaded meshes (may be
// null for package). Deterministic; fails with the status the tool would
// print.
Result<StepResult> run_bake_step(const StepPlan& step, const std::string& input, const Bytes& bytes,
                                 std::map<std::string, std::vector<Bytes>>* earlier,
                                 InputMeshes* meshes);

}  // namespace lodbake
