// Progressive mesh replay (Hoppe 1996 vertex splits, half-edge collapse
// flavour). Split i of vs finds the faces to hand to vt by walking the fan of
// vs counter-clockwise from the face (vs, vr, .) to the face (vs, ., vl) (see
// VertexSplit in formats/mesh/progressive_mesh.h); when the walk meets the
// boundary first (vt was a boundary vertex on an interior edge) the rest of
// vt's faces lie clockwise from (vs, ., vl) to the other end of the
// boundary. Every walk is bounded by the fan's size so that a corrupted
// record cannot loop. Per-vertex face
// lists are small vectors: replay is not the hot path of the toolchain.
#include "lib/simplify/pm_replay.h"

#include <algorithm>
#include <new>
#include <string>

#include "lib/simplify/split_fan.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace {

Status check_attribute(const MeshAttribute& attr, const char* name, size_t vertices) {
  if (!attr.present()) return Status::ok();
  if (attr.binding != AttributeBinding::kPerVertex || attr.components == 0 ||
      attr.values.size() != vertices * attr.components) {
    return invalid_input(std::string("progressive mesh ") + name + " must be per-vertex with " +
                         "one value for each of the " + std::to_string(vertices) + " vertices");
  }
  return Status::ok();
}

}  // namespace

Result<PmRefiner> PmRefiner::create(const ProgressiveMesh& pm) {
  const size_t n0 = pm.base.positions.size();
  const size_t full = pm.full_vertex_count();
  if (full >= kNoVertex) return invalid_input("progressive mesh has too many vertices");
  if (pm.input_vertex.size() != full) {
    return invalid_input("progressive mesh maps " + std::to_string(pm.input_vertex.size()) +
                         " vertices to the input, expected " + std::to_string(full));
  }
  LODBAKE_RETURN_IF_ERROR(check_attribute(pm.normals, "normals", full));
  LODBAKE_RETURN_IF_ERROR(check_attribute(pm.texcoords, "texture coordinates", full));
  PmRefiner r(pm);
  r.mesh_.positions = pm.base.positions;
  r.vertex_faces_.resize(n0);
  for (const MeshAttribute* attr : {&pm.normals, &pm.texcoords}) {
    MeshAttribute& dst = attr == &pm.normals ? r.mesh_.normals : r.mesh_.texcoords;
    if (!attr->present()) continue;
    dst.binding = AttributeBinding::kPerVertex;
    dst.components = attr->components;
  }
  for (size_t v = 0; v < n0; ++v)
    r.copy_attributes(v);
  for (size_t t = 0; t < pm.base.triangles.size(); ++t) {
    const Triangle& tri = pm.base.triangles[t];
    if (tri[0] >= n0 || tri[1] >= n0 || tri[2] >= n0 || tri[0] == tri[1] || tri[1] == tri[2] ||
        tri[0] == tri[2]) {
      return invalid_input("base triangle " + std::to_string(t) +
                           " has an out-of-range or repeated vertex index");
    }
    r.mesh_.triangles.push_back(tri);
    r.add_face(static_cast<uint32_t>(t));
  }
  return r;
}

void PmRefiner::copy_attributes(size_t vertex) {
  for (const MeshAttribute* attr : {&pm_->normals, &pm_->texcoords}) {
    if (!attr->present()) continue;
    MeshAttribute& dst = attr == &pm_->normals ? mesh_.normals : mesh_.texcoords;
    const float* src = &attr->values[vertex * attr->components];
    dst.values.insert(dst.values.end(), src, src + attr->components);
  }
}

void PmRefiner::add_face(uint32_t f) {
  for (uint32_t v : mesh_.triangles[f])
    vertex_faces_[v].push_back(f);
}

void PmRefiner::remove_last_face() {
  const uint32_t f = static_cast<uint32_t>(mesh_.triangles.size() - 1);
  for (uint32_t v : mesh_.triangles[f]) {
    std::vector<uint32_t>& faces = vertex_faces_[v];
    faces.erase(std::find(faces.begin(), faces.end(), f));
  }
  mesh_.triangles.pop_back();
}

Status PmRefiner::split_next() {
  if (applied_ >= pm_->splits.size()) return invalid_input("no vertex split left to apply");
  const VertexSplit& s = pm_->splits[applied_];
  const uint32_t vt = static_cast<uint32_t>(mesh_.positions.size());
  const uint32_t vs = s.vs;
  const uint32_t vl = s.vl;
  const uint32_t vr = s.vr;
  const size_t first_moved = moved_faces_.size();
  LODBAKE_RETURN_IF_ERROR(
      collect_moved_faces(mesh_.triangles, vertex_faces_, vt, s, applied_, &moved_faces_));

  // Apply.
  Undo undo;
  undo.vs_position = mesh_.positions[vs];
  undo.moved_begin = static_cast<uint32_t>(first_moved);
  undo.added_faces = 0;
  mesh_.positions.push_back(s.vt_position);
  mesh_.positions[vs] = s.vs_position;
  copy_attributes(vt);
  vertex_faces_.emplace_back();
  std::vector<uint32_t>& vs_faces = vertex_faces_[vs];
  for (size_t i = first_moved; i < moved_faces_.size(); ++i) {
    const uint32_t f = moved_faces_[i];
    Triangle& t = mesh_.triangles[f];
    t[corner_of(t, vs)] = vt;
    vs_faces.erase(std::find(vs_faces.begin(), vs_faces.end(), f));
    vertex_faces_[vt].push_back(f);
  }
  if (vl != kNoVertex) {
    mesh_.triangles.push_back({vs, vt, vl});
    add_face(static_cast<uint32_t>(mesh_.triangles.size() - 1));
    ++undo.added_faces;
  }
  if (vr != kNoVertex) {
    mesh_.triangles.push_back({vt, vs, vr});
    add_face(static_cast<uint32_t>(mesh_.triangles.size() - 1));
    ++undo.added_faces;
  }
  undo_.push_back(undo);
  ++applied_;
  return Status::ok();
}

Status PmRefiner::collapse_last() {
  if (applied_ == 0) return invalid_input("no vertex split to undo");
  const VertexSplit& s = pm_->splits[applied_ - 1];
  const Undo undo = undo_.back();
  undo_.pop_back();
  const uint32_t vt = static_cast<uint32_t>(mesh_.positions.size() - 1);
  const uint32_t vs = s.vs;
  for (uint32_t i = 0; i < undo.added_faces; ++i)
    remove_last_face();
  for (size_t i = undo.moved_begin; i < moved_faces_.size(); ++i) {
    const uint32_t f = moved_faces_[i];
    Triangle& t = mesh_.triangles[f];
    t[corner_of(t, vt)] = vs;
    vertex_faces_[vs].push_back(f);
  }
  moved_faces_.resize(undo.moved_begin);
  vertex_faces_.pop_back();
  mesh_.positions.pop_back();
  mesh_.positions[vs] = undo.vs_position;
  for (MeshAttribute* attr : {&mesh_.normals, &mesh_.texcoords}) {
    if (attr->present()) attr->values.resize(attr->values.size() - attr->components);
  }
  --applied_;
  return Status::ok();
}

Status PmRefiner::refine_to(size_t vertex_count) {
  const size_t n0 = pm_->base.positions.size();
  if (vertex_count < n0 || vertex_count > pm_->full_vertex_count()) {
    return invalid_input("level of detail of " + std::to_string(vertex_count) +
                         " vertices is outside [" + std::to_string(n0) + ", " +
                         std::to_string(pm_->full_vertex_count()) + "]");
  }
  while (this->vertex_count() < vertex_count)
    LODBAKE_RETURN_IF_ERROR(split_next());
  while (this->vertex_count() > vertex_count)
    LODBAKE_RETURN_IF_ERROR(collapse_last());
  return Status::ok();
}

Result<TriangleMesh> mesh_at_lod(const ProgressiveMesh& pm, size_t vertex_count) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
    LODBAKE_RETURN_IF_ERROR(refiner.refine_to(vertex_count));
    return refiner.mesh();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while refining the progressive mesh");
  }
}

Result<TriangleMesh> map_to_input(const ProgressiveMesh& pm, const TriangleMesh& full) {
  const size_t n = full.positions.size();
  if (pm.input_vertex.size() != n) {
    return invalid_input("progressive mesh maps " + std::to_string(pm.input_vertex.size()) +
                         " vertices, the mesh has " + std::to_string(n));
  }
  std::vector<uint8_t> seen(n, 0);
  for (uint32_t v : pm.input_vertex) {
    if (v >= n || seen[v]) {
      return invalid_input("the input vertex map is not a permutation (entry " + std::to_string(v) +
                           ")");
    }
    seen[v] = 1;
  }
  TriangleMesh out;
  out.positions.resize(n);
  for (size_t v = 0; v < n; ++v)
    out.positions[pm.input_vertex[v]] = full.positions[v];
  out.triangles.reserve(full.triangles.size());
  for (const Triangle& t : full.triangles) {
    out.triangles.push_back({pm.input_vertex[t[0]], pm.input_vertex[t[1]], pm.input_vertex[t[2]]});
  }
  const MeshAttribute* in_attrs[2] = {&full.normals, &full.texcoords};
  MeshAttribute* out_attrs[2] = {&out.normals, &out.texcoords};
  for (int a = 0; a < 2; ++a) {
    const MeshAttribute& in = *in_attrs[a];
    if (in.binding != AttributeBinding::kPerVertex || in.values.size() != n * in.components) {
      continue;
    }
    MeshAttribute& o = *out_attrs[a];
    o.binding = AttributeBinding::kPerVertex;
    o.components = in.components;
    o.values.resize(in.values.size());
    for (size_t v = 0; v < n; ++v) {
      std::copy_n(&in.values[v * in.components], in.components,
                  &o.values[size_t{pm.input_vertex[v]} * in.components]);
    }
  }
  return out;
}

bool same_oriented_triangles(const TriangleMesh& a, const TriangleMesh& b) {
  if (a.positions.size() != b.positions.size() || a.triangles.size() != b.triangles.size()) {
    return false;
  }
  auto canonical = [](const TriangleMesh& m) {
    std::vector<Triangle> out;
    out.reserve(m.triangles.size());
    for (Triangle t : m.triangles) {
      while (t[0] > t[1] || t[0] > t[2])
        t = {t[1], t[2], t[0]};
      out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  return canonical(a) == canonical(b);
}

}  // namespace lodbake
