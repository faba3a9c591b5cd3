// Draco stream header gate (layout: draco/compression/config/
// compression_shared.h, struct DracoHeader: "DRACO", major, minor, encoder
// type, encoder method, 16-bit flags). See draco_header.h for why old
// bitstream versions are refused rather than handed to Draco.
#include "lib/dracoio/draco_header.h"

#include <cstring>
#include <string>

namespace lodbake {
namespace dracoio {

Status check_draco_header(const uint8_t* data, size_t size) {
  if (size < 11 || std::memcmp(data, "DRACO", 5) != 0) {
    return invalid_input("not a Draco file (no 11-byte header starting with 'DRACO')");
  }
  const unsigned major = data[5], minor = data[6], type = data[7], method = data[8];
  if (type == 0) return unsupported("the Draco file holds a point cloud, not a triangle mesh");
  if (type != 1)
    return invalid_input("Draco header has unknown geometry type " + std::to_string(type));
  if (major != 2 || minor != 2) {
    return unsupported("Draco mesh bitstream version " + std::to_string(major) + "." +
                       std::to_string(minor) +
                       " is not supported (only 2.2, written by Draco 1.3 and later)");
  }
  if (method > 1) {
    return invalid_input("Draco header has unknown encoding method " + std::to_string(method));
  }
  return Status::ok();
}

}  // namespace dracoio
}  // namespace lodbake
