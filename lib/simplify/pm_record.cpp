// Progressive mesh recording. Base vertices are numbered in increasing input
// order, then the collapse log is walked backwards: the last collapse's vt is
// the first split's new vertex. Base triangles keep their input order.
// Per-vertex attributes are recorded per vertex identity (the input's value
// of each vertex): exact at every LoD in half mode, where a vertex never
// moves; in optimal mode the PM's attributes are those of the input vertex,
// not the interpolated ones of the simplified mesh.
#include "lib/simplify/pm_record.h"

namespace lodbake {
namespace simplify_internal {
namespace {

MeshAttribute permute_attribute(const MeshAttribute& attr, const std::vector<uint32_t>& order,
                                size_t count) {
  MeshAttribute out;
  if (attr.binding != AttributeBinding::kPerVertex) return out;
  out.binding = AttributeBinding::kPerVertex;
  out.components = attr.components;
  out.values.reserve(count * attr.components);
  for (size_t i = 0; i < count; ++i) {
    const float* src = &attr.values[size_t{order[i]} * attr.components];
    out.values.insert(out.values.end(), src, src + attr.components);
  }
  return out;
}

}  // namespace

ProgressiveMesh record_progressive_mesh(const TriangleMesh& input, const EngineState& state) {
  const size_t n = state.positions.size();
  ProgressiveMesh pm;
  std::vector<uint32_t> pm_id(n, kNoVertex);
  std::vector<uint32_t>& input_vertex = pm.input_vertex;
  input_vertex.reserve(n);
  for (size_t v = 0; v < n; ++v) {
    if (!state.vertex_alive[v]) continue;
    pm_id[v] = static_cast<uint32_t>(input_vertex.size());
    input_vertex.push_back(static_cast<uint32_t>(v));
  }
  const size_t base_count = input_vertex.size();
  for (size_t i = state.log.size(); i-- > 0;) {
    pm_id[state.log[i].vt] = static_cast<uint32_t>(input_vertex.size());
    input_vertex.push_back(state.log[i].vt);
  }

  pm.base.positions.reserve(base_count);
  for (size_t i = 0; i < base_count; ++i) {
    pm.base.positions.push_back(state.positions[input_vertex[i]]);
  }
  for (size_t t = 0; t < state.triangles.size(); ++t) {
    if (!state.triangle_alive[t]) continue;
    const Triangle& tri = state.triangles[t];
    pm.base.triangles.push_back({pm_id[tri[0]], pm_id[tri[1]], pm_id[tri[2]]});
  }
  auto map = [&](uint32_t v) { return v == kNoVertex ? kNoVertex : pm_id[v]; };
  pm.splits.reserve(state.log.size());
  for (size_t i = state.log.size(); i-- > 0;) {
    const CollapseRecord& r = state.log[i];
    VertexSplit s;
    s.vs = pm_id[r.vs];
    s.vl = map(r.vl);
    s.vr = map(r.vr);
    s.vt_position = state.vt_position(i);
    s.vs_position = state.vs_position(i);
    s.error = r.error;
    pm.splits.push_back(s);
  }
  pm.normals = permute_attribute(input.normals, input_vertex, n);
  pm.texcoords = permute_attribute(input.texcoords, input_vertex, n);
  pm.base.normals = permute_attribute(input.normals, input_vertex, base_count);
  pm.base.texcoords = permute_attribute(input.texcoords, input_vertex, base_count);
  return pm;
}

}  // namespace simplify_internal
}  // namespace lodbake
