// What the builder tools say when they build over a whole asset
// (lib/scene/asset_build.h): the input record for META, the one warning
// about attributes, and the per-group report.
#pragma once

#include <functional>
#include <string>
#include <utility>

#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "lib/ingest/meta_input.h"
#include "lib/scene/asset_build.h"
#include "tools/common/cli.h"

namespace lodbake::cli {

// Until structures carry attributes, every build over an asset says so once,
// as a note: the input is fine, the structure is what leaves them out.
inline constexpr char kPositionsOnly[] =
    "the structures hold positions only: the asset's attributes and materials stay in its SCNE "
    "section, not in the levels they refine to (attribute-aware structures: not yet)";
// lodbake-hierarchy with DAGE or VTRE: their progressive mesh has WEDG.
inline constexpr char kHierarchyPmOnly[] =
    "the hierarchy's progressive mesh (VSPL) keeps the asset's attributes (WEDG), and so do "
    "VHIE's selective fronts, DAGE's cuts and the client meshes of replay --mode stream and "
    "--mode vtrees (VTRE's trees index positions; their records take the wedges from WEDG)";
// lodbake-strips without --strips-only: its progressive mesh has WEDG.
inline constexpr char kStripsPmOnly[] =
    "the strips' progressive mesh (VSPL) keeps the asset's attributes (WEDG), and so does every "
    "SETS level recovered (each corner takes its wedge from it); the strips index positions";

// The report of a build over an asset, text or JSON; returns 0.
int print_asset_build(const Tool& tool, const char* schema, const std::string& input,
                      const std::string& output, const AssetBuild& built);

// What differs between the builders' runs over an asset.
struct AssetRun {
  std::string input;   // the asset, or its container
  std::string output;  // the container to write
  bool repair = false;
  bool strict = false;
  const char* schema = "";    // of the JSON report
  const char* progress = "";  // the progress line's label
  // Called once the asset is read, before any mesh is built (e.g. to share
  // a triangle budget among its meshes); may be empty.
  std::function<void(const Scene&)> on_scene;
  // The structure carries the asset's attributes (a progressive mesh with
  // WEDG): no kPositionsOnly warning.
  bool attributes = false;
  // The note in place of kPositionsOnly when the structure keeps the
  // attributes in part; may be null.
  const char* partial_note = nullptr;
};

// The AssetRun of a builder's request: every builder's Request names its
// input, output, --repair and --strict alike; the rest is left at its
// default for the caller to set.
template <typename Request>
AssetRun asset_run(const Request& request, const char* schema, const char* progress) {
  AssetRun run;
  run.input = request.input;
  run.output = request.output;
  run.repair = request.repair;
  run.strict = request.strict;
  run.schema = schema;
  run.progress = progress;
  return run;
}

// Sets run->on_scene to read what every mesh's build needs from the scene
// once: `read(scene)`'s value into *value, or its error into *error (which
// the build then returns, so that the run stops with it).
template <typename T, typename Read>
void read_on_scene(AssetRun* run, Read read, T* value, Status* error) {
  run->on_scene = [read, value, error](const Scene& scene) {
    Result<T> all = read(scene);
    if (all.is_ok()) {
      *value = std::move(all).value();
    } else {
      *error = all.status();
    }
  };
}

// A builder's whole run over an asset (`bytes`: the input's content):
// reads it, builds every mesh with `build` (build_asset()), writes the
// container, warns (kPositionsOnly once) and reports. `meta` gives the tool
// and its options; its input is set here. Returns the exit code.
int run_asset_build(const Tool& tool, const AssetRun& run, MetaSection meta, const Bytes& bytes,
                    const MeshBuilder& build);

}  // namespace lodbake::cli
