// The import path every tool runs on an input mesh: read the file, parse it,
// check it, repair it when asked, and decide whether the tool can take it.
// Tools call this once and print what it reports.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/check/mesh_check.h"
#include "lib/check/mesh_policy.h"
#include "lib/meshio/import_report.h"
#include "lib/repair/mesh_repair.h"

namespace lodbake {

struct LoadOptions {
  bool repair = false;  // run repair_mesh() before the policy is applied
  // Drop vertices no triangle uses (after repair, before the policy), for
  // tools that store the mesh: they would only widen its bounding box.
  bool drop_unreferenced = false;
  // What the calling tool cannot take; nothing means "accept any mesh the
  // reader could parse" (the linter's choice).
  std::optional<UsePolicy> policy = UsePolicy();
};

struct LoadedMesh {
  TriangleMesh mesh;                   // as imported, or repaired
  ImportReport import;                 // format, triangulation, ignored attributes
  MeshCheckReport check;               // of the mesh as imported
  std::optional<RepairReport> repair;  // when LoadOptions::repair
  std::optional<MeshCheckReport> check_after_repair;
  uint64_t dropped_unreferenced = 0;  // by LoadOptions::drop_unreferenced
  uint64_t file_bytes = 0;
  std::string sha256;  // of the file's bytes
};

// Loads `path`. Fails with the reader's status (kIo, kInvalidInput,
// kUnsupported), the repair's, or, when the mesh breaks `options.policy`,
// with kInvalidInput naming the first problem. `loaded` is filled as far as
// it got either way.
Status load_mesh(const std::string& path, const LoadOptions& options, LoadedMesh* loaded);

// The same for a file the caller has already read; `path` names it in
// messages and hints its format.
Status load_mesh_bytes(const std::string& path, Bytes bytes, const LoadOptions& options,
                       LoadedMesh* loaded);

}  // namespace lodbake
