// Fuzz target for a bare FANH payload: summary, decode, structure checks,
// the canonical round trip (re-encoding what decoded gives the input back
// byte for byte), and, for small hierarchies, the replay check and the
// runtime over a synthetic mesh of the stated counts (every operation on a
// hostile hierarchy must be refused cleanly or keep the mesh consistent),
// with the fronts' wedges of a one-wedge-per-vertex table followed
// (FanWedges: refused cleanly, or the input's corners at the finest front).
#include <cstdint>

#include "formats/sections/fanh.h"
#include "lib/fanmerge/fan_runtime.h"
#include "lib/fanmerge/fan_wedges.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using namespace lodbake::fuzz;
  Result<FanhSummary> summary = read_fanh_summary(data, size);
  Result<FanHierarchy> h = decode_fanh(data, size);
  if (!h.is_ok()) {
    require_decode_error(h.status(), "FANH decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "FANH decodes but its summary does not");
  require(validate_fanh_structure(h.value()).empty(), "decoded FANH fails its structure check");
  Result<Bytes> again = encode_fanh(h.value());
  require(again.is_ok(), "decoded FANH does not re-encode");
  require_same_bytes(again.value(), data, size, "FANH round trip changed the bytes");
  (void)fanh_stats(h.value());
  const FanHierarchy& fan = h.value();
  if (fan.vertex_count < 3 || fan.vertex_count > 4096 || fan.triangle_count > 8192) return 0;
  TriangleMesh mesh;
  mesh.positions.resize(fan.vertex_count);
  for (uint32_t v = 0; v < fan.vertex_count; ++v)
    mesh.positions[v] = {static_cast<float>(v % 7), static_cast<float>(v % 5), float(v % 3)};
  for (uint32_t t = 0; t < fan.triangle_count; ++t)
    mesh.triangles.push_back(
        {t % fan.vertex_count, (t + 1) % fan.vertex_count, (t + 2) % fan.vertex_count});
  (void)validate_fanh(fan, mesh);
  Result<FanRuntime> rt = FanRuntime::create(mesh, fan);
  require(rt.is_ok(), "a structurally valid FANH does not load");
  FanRuntime& r = rt.value();
  PmWedges wedges;
  wedges.wedge_primitive.assign(fan.vertex_count, 0);
  for (uint32_t v = 0; v < fan.vertex_count; ++v) {
    wedges.wedge_vertex.push_back(v);
    wedges.wedge_home.push_back(v);
  }
  wedges.base = mesh.triangles;
  wedges.moved_offset.assign(1, 0);
  Result<FanWedges> fronts = FanWedges::create(mesh, fan, wedges);
  if (fronts.is_ok()) {
    Result<std::vector<std::array<uint32_t, 3>>> finest = fronts.value().corners(r);
    require(finest.is_ok() && finest.value() == wedges.base,
            "the finest fan front does not have the input's wedges");
  }
  (void)r.merge_all();
  if (fronts.is_ok()) (void)fronts.value().corners(r);
  for (uint32_t node = r.leaf_count(); node < r.node_count(); ++node) {
    (void)r.retreat(node);
    (void)r.advance(node);
  }
  if (fronts.is_ok()) (void)fronts.value().corners(r);
  (void)r.split_all();
  require(r.active().size() == r.vertex_count(), "active list and vertex count disagree");
  return 0;
}
