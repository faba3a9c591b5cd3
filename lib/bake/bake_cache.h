// lodbake-bake's content cache: a step whose inputs (the input's bytes and
// name, and every buffer, image or material file it references), options
// and lodbake version are unchanged is not baked again; its files come from
// the cache folder. One SHA-256 key per step; a package step's key covers
// the keys of the steps it merges.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/bake/bake_steps.h"
#include "lib/bake/recipe.h"

namespace lodbake {

// What an input's outputs depend on besides the options: its base name
// (META records it), the SHA-256 of its bytes and, for an asset (or an OBJ
// read as a scene), each file it references, by its path relative to the
// input's folder, with its SHA-256 (null when missing: adding it later
// changes the key). Reads the asset to find them.
nlohmann::json input_fingerprint(const std::string& input, const Bytes& bytes);

// The files of `fingerprint`'s resources that exist, as paths from where
// `input` is named (joined to its folder): what a workflow engine must
// watch besides the input itself (lodbake-bake --list prints them).
std::vector<std::string> referenced_files(const std::string& input,
                                          const nlohmann::json& fingerprint);

// The key of `step` of an input with `fingerprint`; `merged` holds the keys
// of the steps a package step merges, in its order (empty otherwise).
std::string step_key(const nlohmann::json& fingerprint, const StepPlan& step,
                     const std::vector<std::string>& merged);

// A cache folder: DIR/ab/abcdef.../ holds a step's files (0, 1, ...) and
// step.json (its warnings and report), written last, so that an entry
// whose step.json exists is complete.
class BakeCache {
 public:
  explicit BakeCache(std::string folder) : folder_(std::move(folder)) {}
  // The step's files (in the plan's order, paths set from `step.outputs`),
  // warnings and report, or nothing on a miss or a damaged entry.
  std::optional<StepResult> load(const std::string& key, const StepPlan& step) const;
  // Stores a baked step; kIo when the folder cannot be written.
  Status store(const std::string& key, const StepResult& result) const;

 private:
  std::string entry(const std::string& key) const;
  std::string folder_;
};

// The default cache folder: $LODBAKE_CACHE_DIR, else $XDG_CACHE_HOME/lodbake,
// else $HOME/.cache/lodbake, else .lodbake-cache.
std::string default_bake_cache_folder();

}  // namespace lodbake
