// import_mesh(): the one entry point tools use to turn a file's bytes into a
// TriangleMesh. Detects the format from the content first (magic bytes,
// keywords) and from the file name only when the content is ambiguous, so a
// PLY saved as .obj is read as PLY; gzip-compressed input is decompressed
// (with a bound on the decompressed size) first.
#pragma once

#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

enum class MeshFormat { kObj, kOff, kPly, kStl, kGltf, kGlb, kDraco };

const char* mesh_format_name(MeshFormat format);

// The format of `bytes` (already decompressed), using `file_name`'s extension
// as a hint only when the content does not decide it.
Result<MeshFormat> detect_mesh_format(const std::string& file_name, const Bytes& bytes);

// Parses `bytes` read from `file_name`, which gives the format hint and the
// folder a .gltf's external buffers are read from (confined to it: see
// read_resource(); "." for a bare name). `resources`, when given, replaces
// that folder (an empty SceneResources reads from memory only).
Result<TriangleMesh> import_mesh(const std::string& file_name, const Bytes& bytes,
                                 ImportReport* report, const SceneResources* resources = nullptr);

// Reads and parses a file.
Result<TriangleMesh> import_mesh_file(const std::string& path, ImportReport* report);

}  // namespace lodbake
