// Fuzz target for the Draco BASE decoder (codec 2): a bare Draco BASE
// payload. Invariants: a decoded mesh is a storable BASE (encode_base
// accepts it and decode_base reads it back equal), and encoding it with
// Draco again at the stored options keeps every triangle's vertex ids.
#include <cstdint>

#include "formats/sections/base.h"
#include "formats/sections/draco_codec.h"
#include "tests/fuzz/fuzz_section_checks.h"

using namespace lodbake;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Result<TriangleMesh> mesh = decode_base_draco(data, size);
  if (!mesh.is_ok()) return 0;
  Result<Bytes> raw = encode_base(mesh.value(), BaseEncodeOptions{});
  if (!raw.is_ok()) return 0;  // e.g. non-finite values Draco let through: the reader refuses
  Result<TriangleMesh> back = decode_base(raw.value().data(), raw.value().size());
  fuzz::require(back.is_ok() && back.value() == mesh.value(), "raw BASE round trip differs");
  Result<DracoOptions> options = read_draco_base_options(data, size);
  fuzz::require(options.is_ok(), "decoded payload without readable options");
  Result<Bytes> again = encode_base_draco(mesh.value(), options.value());
  if (!again.is_ok()) return 0;  // meshes without triangles or with values Draco cannot take
  Result<TriangleMesh> redecoded = decode_base_draco(again.value().data(), again.value().size());
  fuzz::require(redecoded.is_ok() && redecoded.value().triangles == mesh.value().triangles,
                "Draco BASE re-encoding changed the triangles");
  return 0;
}
