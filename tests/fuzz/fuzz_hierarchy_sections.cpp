// Fuzz target for the VHIE and RFIN decoders. Input: a 4-byte little-endian
// length n, then n bytes of VHIE payload, then the RFIN payload. VHIE is
// decoded onto a synthetic base mesh of its stored root count; a decoded
// hierarchy must pass validate_hierarchy() and re-encode to the same bytes
// (the format has one canonical form); RFIN is decoded against it and its
// values must be finite and non-negative with half-angles in [0, pi].
#include <cmath>
#include <cstdint>
#include <cstring>

#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using lodbake::fuzz::require;
  using lodbake::fuzz::require_decode_error;
  using lodbake::fuzz::require_same_bytes;
  if (size < 4) return 0;
  uint32_t n = 0;
  std::memcpy(&n, data, 4);
  data += 4;
  size -= 4;
  if (n > size) n = static_cast<uint32_t>(size);
  Result<VhieSummary> summary = read_vhie_summary(data, n);
  TriangleMesh base;
  if (summary.is_ok() && summary.value().root_count <= fuzz::kMaxSyntheticBaseVertices) {
    base = fuzz::synthetic_base(summary.value().root_count, 0);
  }
  Result<VertexHierarchy> h = decode_vhie(data, n, base);
  if (!h.is_ok()) {
    require_decode_error(h.status(), "VHIE decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "VHIE decodes but its summary does not");
  require(validate_hierarchy(h.value()).empty(), "decoded VHIE fails validation");
  const HierarchyShape shape = hierarchy_shape(h.value());
  require(shape.depth == summary.value().depth && shape.nodes == summary.value().node_count,
          "VHIE summary disagrees with the decoded hierarchy");
  Result<Bytes> again = encode_vhie(h.value());
  require(again.is_ok(), "decoded VHIE cannot be encoded");
  require_same_bytes(again.value(), data, n, "VHIE round trip is not byte-exact");
  Result<std::vector<NodeRefinement>> rfin = decode_rfin(data + n, size - n, h.value());
  if (!rfin.is_ok()) {
    require_decode_error(rfin.status(), "RFIN decode error without LBK-E023");
    return 0;
  }
  for (const NodeRefinement& r : rfin.value()) {
    require(std::isfinite(r.radius) && r.radius >= 0 && std::isfinite(r.mu2) && r.mu2 >= 0 &&
                std::isfinite(r.delta2) && r.delta2 >= 0 && r.cone_half_angle >= 0 &&
                r.cone_half_angle <= 3.1416f,
            "RFIN value out of range");
  }
  return 0;
}
