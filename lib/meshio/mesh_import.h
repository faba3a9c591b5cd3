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

// A mesh file's content as its parser takes it: decompressed when it was
// gzip (with a note in the report), its format detected by content first.
struct MeshContent {
  MeshFormat format = MeshFormat::kObj;
  std::string file_name;  // the name without a ".gz" the content came out of
  Bytes inflated;         // the decompressed content, when `decompressed`
  bool decompressed = false;

  // The bytes to parse: `inflated`, or the caller's `original` bytes.
  const Bytes& bytes(const Bytes& original) const { return decompressed ? inflated : original; }
};

// Decompresses (gzip, bounded) and detects the format of `bytes` read from
// `file_name`, noting in `report` a decompression and a content that
// contradicts the name. Fails on an empty file, a corrupt or oversized gzip
// stream, and a format neither the content nor the name tells.
Result<MeshContent> prepare_mesh_content(const std::string& file_name, const Bytes& bytes,
                                         ImportReport* report);

// Parses `bytes` read from `file_name`, which gives the format hint and the
// folder a .gltf's external buffers are read from (confined to it: see
// read_resource(); "." for a bare name). `resources`, when given, replaces
// that folder (an empty SceneResources reads from memory only).
Result<TriangleMesh> import_mesh(const std::string& file_name, const Bytes& bytes,
                                 ImportReport* report, const SceneResources* resources = nullptr);

// Reads and parses a file.
Result<TriangleMesh> import_mesh_file(const std::string& path, ImportReport* report);

}  // namespace lodbake
