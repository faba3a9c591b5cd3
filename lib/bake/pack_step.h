// The packing step of lodbake-pack on one input, shared with lodbake-bake
// so that both write the same bytes: a mesh's container (META + BASE,
// float32 or quantized positions) and META's options for a mesh or an asset.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

// META's options: the repair flag and the quantization (null for float32).
nlohmann::json pack_meta_options(bool repair, int quantize_bits);

struct PackedMesh {
  Bytes file;
  uint64_t meta_bytes = 0;
  uint64_t base_bytes = 0;
};

// META (lodbake-pack, pack_meta_options(), `input`, the mesh's counts) and
// BASE, positions quantized to `quantize_bits` bits unless 0.
Result<PackedMesh> pack_mesh(const TriangleMesh& mesh, const MetaInput& input, bool repair,
                             int quantize_bits);

}  // namespace lodbake
