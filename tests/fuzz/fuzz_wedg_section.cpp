// Fuzz target for a bare WEDG payload: counts are bounded by the payload
// before anything is allocated; what decodes must encode back to the same
// bytes.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "formats/sections/wedg.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::Result<lodbake::PmWedges> wedges = lodbake::decode_wedg(data, size);
  if (!wedges.is_ok()) return 0;
  lodbake::Result<lodbake::Bytes> again = lodbake::encode_wedg(wedges.value());
  if (!again.is_ok()) std::abort();
  if (again.value().size() != size || !std::equal(again.value().begin(), again.value().end(), data))
    std::abort();
  return 0;
}
