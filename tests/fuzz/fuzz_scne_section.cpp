// Fuzz target for a bare SCNE payload: the map and the GLB header are
// checked; what decodes must encode back to the same bytes.
#include <cstdint>
#include <cstdlib>

#include "formats/sections/scne.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::Result<lodbake::SceneSection> section = lodbake::decode_scne(data, size);
  if (!section.is_ok()) return 0;
  lodbake::Result<lodbake::Bytes> again = lodbake::encode_scne(section.value());
  if (!again.is_ok()) std::abort();
  lodbake::Result<lodbake::SceneSection> twice =
      lodbake::decode_scne(again.value().data(), again.value().size());
  if (!twice.is_ok() || !(twice.value() == section.value())) std::abort();
  return 0;
}
