// Renumbering the vertices for locality (vertex_order.h). First use in
// triangle order is the simplest order that follows the triangles and costs
// one sweep; a spatial order (Morton) with the triangles sorted to match did
// a little better in a trial, but reordering the triangles changes the
// listing order, hence the tie order and the collapse sequence.
#include "lib/simplify/vertex_order.h"

namespace lodbake {
namespace simplify_internal {
namespace {

MeshAttribute gathered(const MeshAttribute& attr, const std::vector<uint32_t>& order) {
  if (attr.binding != AttributeBinding::kPerVertex) return attr;
  MeshAttribute out;
  out.binding = attr.binding;
  out.components = attr.components;
  out.values.resize(attr.values.size());
  const uint32_t c = attr.components;
  for (size_t i = 0; i < order.size(); ++i) {
    for (uint32_t k = 0; k < c; ++k)
      out.values[i * c + k] = attr.values[size_t{order[i]} * c + k];
  }
  return out;
}

MeshAttribute scattered(const MeshAttribute& attr, const std::vector<uint32_t>& order) {
  if (attr.binding != AttributeBinding::kPerVertex) return attr;
  MeshAttribute out = attr;
  const uint32_t c = attr.components;
  for (size_t i = 0; i < order.size(); ++i) {
    for (uint32_t k = 0; k < c; ++k)
      out.values[size_t{order[i]} * c + k] = attr.values[i * c + k];
  }
  return out;
}

}  // namespace

bool locality_order(const TriangleMesh& mesh, std::vector<uint32_t>* order) {
  const size_t n = mesh.positions.size();
  order->clear();
  std::vector<uint8_t> seen(n, 0);
  order->reserve(n);
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t v : t) {
      if (v >= n) {
        order->clear();
        return false;
      }
      if (seen[v]) continue;
      seen[v] = 1;
      order->push_back(v);
    }
  }
  for (uint32_t v = 0; v < n; ++v) {
    if (!seen[v]) order->push_back(v);
  }
  return true;
}

TriangleMesh renumbered_mesh(const TriangleMesh& mesh, const std::vector<uint32_t>& order) {
  const size_t n = order.size();
  std::vector<uint32_t> internal(n);
  for (uint32_t i = 0; i < n; ++i)
    internal[order[i]] = i;
  TriangleMesh out;
  out.positions.resize(n);
  for (size_t i = 0; i < n; ++i)
    out.positions[i] = mesh.positions[order[i]];
  out.triangles.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    out.triangles[t] = {internal[tri[0]], internal[tri[1]], internal[tri[2]]};
  }
  out.normals = gathered(mesh.normals, order);
  out.texcoords = gathered(mesh.texcoords, order);
  return out;
}

void restore_input_ids(const std::vector<uint32_t>& order, EngineState* state) {
  const size_t n = order.size();
  std::vector<Vec3f> positions(n);
  std::vector<uint8_t> alive(n);
  for (size_t i = 0; i < n; ++i) {
    positions[order[i]] = state->positions[i];
    alive[order[i]] = state->vertex_alive[i];
  }
  state->positions = std::move(positions);
  state->vertex_alive = std::move(alive);
  for (Triangle& t : state->triangles) {
    for (uint32_t& v : t)
      v = order[v];
  }
  auto input_id = [&order](uint32_t v) { return v == kNoVertex ? kNoVertex : order[v]; };
  for (CollapseRecord& r : state->log) {
    r.vt = order[r.vt];
    r.vs = order[r.vs];
    r.vl = input_id(r.vl);
    r.vr = input_id(r.vr);
  }
  state->normals = scattered(state->normals, order);
  state->texcoords = scattered(state->texcoords, order);
}

}  // namespace simplify_internal
}  // namespace lodbake
