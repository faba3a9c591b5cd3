// The import path every tool runs on an input mesh: read the file, parse it,
// check it, repair it when asked or when the tool needs it, and decide
// whether the tool can take it. Tools call this once and print what it
// reports.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/check/mesh_check.h"
#include "lib/check/mesh_policy.h"
#include "lib/meshio/import_report.h"
#include "lib/repair/mesh_repair.h"

namespace lodbake {

struct LoadOptions {
  // --repair: run repair_mesh() whatever the mesh has (it also drops the
  // triangles around non-finite coordinates) before the policy is applied.
  bool repair = false;
  // Without --repair, a mesh that breaks `policy` only through problems
  // repair_mesh() fixes by default (fixed_by_default_repair(): non-manifold
  // edges and vertices, degenerate and duplicate triangles, inconsistent
  // orientation) is repaired anyway and LoadedMesh says so. --strict refuses
  // it instead, naming the first problem.
  bool strict = false;
  // Make per-corner normals and texture coordinates per-vertex first, by
  // splitting vertices on attribute seams (split_corner_attributes()), for
  // tools that record a progressive mesh, which holds per-vertex attributes
  // only. Runs before the check, so that a split that leaves a vertex with
  // separate fans is repaired like any other.
  bool per_vertex_attributes = false;
  // Drop vertices no triangle uses (after repair, before the policy), for
  // tools that store the mesh: they would only widen its bounding box.
  bool drop_unreferenced = false;
  // What the calling tool cannot take; nothing means "accept any mesh the
  // reader could parse" (the linter's choice). The default is what the
  // edge-collapse engine and every structure built on it need.
  std::optional<UsePolicy> policy = UsePolicy::two_manifold();
  // The threads the check may use (the tool's --threads; 0: the caller's
  // task arena, every core at the top level or a bake's --jobs).
  unsigned threads = 0;
};

struct LoadedMesh {
  TriangleMesh mesh;                   // as imported, or repaired
  ImportReport import;                 // format, triangulation, ignored attributes
  uint64_t seam_vertices = 0;          // added by LoadOptions::per_vertex_attributes
  MeshCheckReport check;               // of the mesh as imported (and split on seams)
  std::optional<RepairReport> repair;  // when LoadOptions::repair, or repaired by default
  bool repaired_by_default = false;    // `repair` is the default repair's, not --repair's
  std::optional<MeshCheckReport> check_after_repair;
  uint64_t dropped_unreferenced = 0;  // by LoadOptions::drop_unreferenced
  uint64_t file_bytes = 0;
  std::string sha256;  // of the file's bytes
  // A container's original input as its META records it (a container is
  // read as the mesh it stands for, lib/ingest/container_mesh.h).
  std::optional<MetaInput> original_input;
  // For a container: what its mesh is ("progressive mesh" or "base mesh").
  std::string container_source;
};

// Loads `path`. Fails with the reader's status (kIo, kInvalidInput,
// kUnsupported), the repair's, or, when the mesh breaks `options.policy`
// (and the default repair cannot fix it, or `options.strict` forbids it),
// with kInvalidInput naming the first problem ("--strict: ..." when only
// --strict refused it). `loaded` is filled as far as it got either way; its
// `repair` only on success.
Status load_mesh(const std::string& path, const LoadOptions& options, LoadedMesh* loaded);

// The same for a file the caller has already read; `path` names it in
// messages and hints its format.
Status load_mesh_bytes(const std::string& path, Bytes bytes, const LoadOptions& options,
                       LoadedMesh* loaded);

// The parsing part of load_mesh_bytes(): fills the mesh, the import report,
// the file's size and hash and, for a container, what it stands for.
Status parse_mesh_bytes(const std::string& path, Bytes bytes, LoadedMesh* loaded);

// Whether LoadOptions::per_vertex_attributes would change `mesh` (it has
// per-corner normals or texture coordinates).
bool has_per_corner_attributes(const TriangleMesh& mesh);

// The steps after parsing, on loaded->mesh already in place (a mesh that
// comes from elsewhere than a file, e.g. a scene mesh's welded topology):
// seam split, check, repair, policy, unreferenced vertices.
Status prepare_mesh(const LoadOptions& options, LoadedMesh* loaded);

}  // namespace lodbake
