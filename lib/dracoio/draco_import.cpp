// Draco (.drc) import: draco::Decoder on the bytes, then the conversion of
// draco_convert.h. Draco validates its own bitstream (header, version,
// connectivity) once draco_header.cpp has refused legacy bitstream versions;
// the conversion then range-checks everything it reads, and every exception
// is caught here. Point clouds are refused: lodbake needs triangles.
#include <new>
#include <string>

#include "draco/compression/decode.h"
#include "draco/core/decoder_buffer.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_header.h"
#include "lib/dracoio/draco_io.h"

namespace lodbake {
namespace {

Result<TriangleMesh> parse_draco_unchecked(const uint8_t* data, size_t size, ImportReport* report) {
  LODBAKE_RETURN_IF_ERROR(dracoio::check_draco_header(data, size));
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    return invalid_input("Draco decoding failed: " + decoded.status().error_msg_string());
  }
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (mesh->num_faces() == 0) return invalid_input("the Draco mesh has no triangles");
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh out, dracoio::mesh_from_draco(*mesh, report));
  if (report != nullptr) {
    report->format = "draco";
    report->file_faces = out.triangles.size();
  }
  return out;
}

}  // namespace

Result<TriangleMesh> parse_draco(const uint8_t* data, size_t size, ImportReport* report) {
  try {
    return parse_draco_unchecked(data, size, report);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding the Draco mesh");
  } catch (const std::exception& e) {
    return invalid_input(std::string("Draco decoding failed: ") + e.what());
  }
}

}  // namespace lodbake
