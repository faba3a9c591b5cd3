// Conversions between draco::Mesh and lodbake meshes. A decoded Draco mesh
// indexes attribute values through points (one point per distinct
// combination of attribute values); lodbake's mesh has one vertex per
// position and per-vertex or per-corner attributes. Decoded data is never
// trusted: face point indices and point -> value mappings are range-checked
// before any value is read.
#include "lib/dracoio/draco_convert.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

std::string att_name(const draco::PointAttribute& att) {
  return draco::GeometryAttribute::TypeToString(att.attribute_type());
}

}  // namespace

// The attribute holds numbers, and every point's mapping leads to a stored
// value. DT_BOOL is refused before any read: Draco's ConvertValue loads it as
// a C++ bool, which is undefined for decoded bytes other than 0 and 1.
Status check_mapping(const draco::PointAttribute& att, uint32_t num_points) {
  if (att.data_type() < draco::DT_INT8 || att.data_type() > draco::DT_FLOAT64) {
    return invalid_input("Draco " + att_name(att) + " attribute has data type " +
                         str(static_cast<uint64_t>(att.data_type())) + ", not a number type");
  }
  if (att.is_mapping_identity()) {
    if (att.size() < num_points) {
      return invalid_input("Draco " + att_name(att) + " attribute has " + str(att.size()) +
                           " values for " + str(num_points) + " points");
    }
    return Status::ok();
  }
  if (att.indices_map_size() < num_points) {
    return invalid_input("Draco " + att_name(att) + " attribute maps " +
                         str(att.indices_map_size()) + " of " + str(num_points) + " points");
  }
  for (uint32_t p = 0; p < num_points; ++p) {
    if (att.mapped_index(draco::PointIndex(p)).value() >= att.size()) {
      return invalid_input("Draco " + att_name(att) + " attribute maps point " + str(p) +
                           " to value " + str(att.mapped_index(draco::PointIndex(p)).value()) +
                           " of " + str(att.size()));
    }
  }
  return Status::ok();
}

namespace {

Status read_value(const draco::PointAttribute& att, uint32_t index, uint32_t components,
                  float* out) {
  if (!att.ConvertValue<float>(draco::AttributeValueIndex(index), static_cast<int8_t>(components),
                               out)) {
    return invalid_input("Draco " + att_name(att) + " value " + str(index) +
                         " cannot be read as float");
  }
  return Status::ok();
}

Status read_all_values(const draco::PointAttribute& att, uint32_t components,
                       std::vector<float>* out) {
  out->resize(att.size() * components);
  for (uint32_t i = 0; i < att.size(); ++i) {
    LODBAKE_RETURN_IF_ERROR(read_value(att, i, components, &(*out)[size_t{i} * components]));
  }
  return Status::ok();
}

uint32_t value_of(const draco::PointAttribute& att, uint32_t point) {
  return att.mapped_index(draco::PointIndex(point)).value();
}

}  // namespace

Status check_faces(const draco::Mesh& mesh) {
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= mesh.num_points()) {
        return invalid_input("Draco face " + str(f) + " uses point " + str(face[k].value()) +
                             " of " + str(mesh.num_points()));
      }
    }
  }
  return Status::ok();
}

namespace {

// The first NORMAL or TEX_COORD attribute as a per-vertex attribute over the
// position values when the mapping allows it, per corner otherwise.
Result<MeshAttribute> convert_attribute(const draco::Mesh& mesh, const draco::PointAttribute& pos,
                                        const draco::PointAttribute& att, uint32_t components) {
  LODBAKE_RETURN_IF_ERROR(check_mapping(att, mesh.num_points()));
  MeshAttribute out;
  out.components = components;
  std::vector<int64_t> value_of_vertex(pos.size(), -1);
  bool per_vertex = true;
  for (uint32_t p = 0; p < mesh.num_points() && per_vertex; ++p) {
    int64_t& slot = value_of_vertex[value_of(pos, p)];
    const int64_t a = value_of(att, p);
    if (slot < 0) slot = a;
    per_vertex = slot == a;
  }
  if (per_vertex) {
    out.binding = AttributeBinding::kPerVertex;
    out.values.assign(pos.size() * components, 0.0f);
    for (size_t v = 0; v < value_of_vertex.size(); ++v) {
      if (value_of_vertex[v] < 0) continue;  // a position no point uses
      LODBAKE_RETURN_IF_ERROR(read_value(att, static_cast<uint32_t>(value_of_vertex[v]), components,
                                         &out.values[v * components]));
    }
    return out;
  }
  out.binding = AttributeBinding::kPerCorner;
  LODBAKE_RETURN_IF_ERROR(read_all_values(att, components, &out.values));
  out.corners.resize(mesh.num_faces());
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k)
      out.corners[f][k] = value_of(att, face[k].value());
  }
  return out;
}

void add_note(ImportReport* report, const std::string& note) {
  if (report == nullptr) return;
  if (std::find(report->notes.begin(), report->notes.end(), note) == report->notes.end()) {
    report->notes.push_back(note);
  }
}

// Point order helper for export: one Draco point per distinct corner tuple.
struct PointKey {
  uint32_t vertex, normal, texcoord;
  bool operator<(const PointKey& o) const {
    if (vertex != o.vertex) return vertex < o.vertex;
    if (normal != o.normal) return normal < o.normal;
    return texcoord < o.texcoord;
  }
  bool operator==(const PointKey& o) const {
    return vertex == o.vertex && normal == o.normal && texcoord == o.texcoord;
  }
};

uint32_t corner_value(const MeshAttribute& att, const TriangleMesh& mesh, size_t t, int k) {
  switch (att.binding) {
    case AttributeBinding::kPerCorner:
      return att.corners[t][k];
    case AttributeBinding::kPerVertex:
      return mesh.triangles[t][k];
    default:
      return 0;
  }
}

void add_float_attribute(draco::Mesh* out, draco::GeometryAttribute::Type type,
                         const MeshAttribute& src, uint32_t components,
                         const std::vector<uint32_t>& point_values) {
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, static_cast<uint8_t>(components), draco::DT_FLOAT32, false,
          sizeof(float) * components, 0);
  const size_t count = src.value_count();
  const int id = out->AddAttribute(ga, false, static_cast<uint32_t>(count));
  draco::PointAttribute* att = out->attribute(id);
  for (size_t i = 0; i < count; ++i) {
    att->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                           &src.values[i * components]);
  }
  att->SetExplicitMapping(point_values.size());
  for (size_t p = 0; p < point_values.size(); ++p) {
    att->SetPointMapEntry(draco::PointIndex(static_cast<uint32_t>(p)),
                          draco::AttributeValueIndex(point_values[p]));
  }
}

}  // namespace

Result<TriangleMesh> mesh_from_draco(const draco::Mesh& mesh, ImportReport* report) {
  const draco::PointAttribute* pos = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (pos == nullptr) return invalid_input("the Draco mesh has no POSITION attribute");
  if (pos->num_components() != 3) {
    return invalid_input("Draco POSITION has " + str(pos->num_components()) +
                         " components, 3 expected");
  }
  if (pos->size() > 0xFFFFFFFEull) return invalid_input("Draco mesh has too many vertices");
  LODBAKE_RETURN_IF_ERROR(check_mapping(*pos, mesh.num_points()));
  LODBAKE_RETURN_IF_ERROR(check_faces(mesh));
  TriangleMesh out;
  std::vector<float> xyz;
  LODBAKE_RETURN_IF_ERROR(read_all_values(*pos, 3, &xyz));
  out.positions.resize(pos->size());
  for (size_t v = 0; v < out.positions.size(); ++v) {
    out.positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
  }
  out.triangles.resize(mesh.num_faces());
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k)
      out.triangles[f][k] = value_of(*pos, face[k].value());
  }
  const draco::PointAttribute* normal = nullptr;
  const draco::PointAttribute* texcoord = nullptr;
  for (int32_t i = 0; i < mesh.num_attributes(); ++i) {
    const draco::PointAttribute* att = mesh.attribute(i);
    if (att == pos) continue;
    if (att->attribute_type() == draco::GeometryAttribute::NORMAL && normal == nullptr &&
        att->num_components() == 3) {
      normal = att;
    } else if (att->attribute_type() == draco::GeometryAttribute::TEX_COORD &&
               texcoord == nullptr && att->num_components() == 2) {
      texcoord = att;
    } else {
      add_note(report, "ignored Draco attribute " + att_name(*att) + " (" +
                           str(att->num_components()) + " components)");
    }
  }
  if (normal != nullptr) {
    LODBAKE_ASSIGN_OR_RETURN(out.normals, convert_attribute(mesh, *pos, *normal, 3));
  }
  if (texcoord != nullptr) {
    LODBAKE_ASSIGN_OR_RETURN(out.texcoords, convert_attribute(mesh, *pos, *texcoord, 2));
  }
  if (mesh.GetMetadata() != nullptr) add_note(report, "ignored Draco metadata");
  return out;
}

Status check_mesh_for_export(const TriangleMesh& mesh) {
  const size_t v = mesh.positions.size();
  if (mesh.triangles.empty()) return invalid_input("the mesh has no triangles");
  if (v > 0xFFFFFFFEull) return invalid_input("the mesh has more than 2^32 - 2 vertices");
  for (size_t i = 0; i < v; ++i) {
    for (float c : mesh.positions[i]) {
      // glTF requires POSITION min/max, which JSON cannot hold for NaN or inf.
      if (!std::isfinite(c)) {
        return invalid_input("vertex " + str(i) +
                             " has a non-finite coordinate, which glTF cannot store");
      }
    }
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t i : mesh.triangles[t]) {
      if (i >= v) {
        return invalid_input("triangle " + str(t) + ": vertex index " + str(i) + " out of range (" +
                             str(v) + " vertices)");
      }
    }
  }
  const std::pair<const MeshAttribute*, const char*> attributes[] = {
      {&mesh.normals, "normals"}, {&mesh.texcoords, "texture coordinates"}};
  const uint32_t expected_components[] = {3, 2};
  for (int a = 0; a < 2; ++a) {
    const MeshAttribute& att = *attributes[a].first;
    const std::string name = attributes[a].second;
    if (!att.present()) continue;
    if (att.components != expected_components[a] || att.values.size() % att.components != 0) {
      return invalid_input(name + " have " + str(att.components) + " components, " +
                           str(expected_components[a]) + " expected");
    }
    if (att.binding == AttributeBinding::kPerVertex && att.value_count() != v) {
      return invalid_input(name + " are per vertex but have " + str(att.value_count()) +
                           " values for " + str(v) + " vertices");
    }
    if (att.binding == AttributeBinding::kPerCorner) {
      if (att.corners.size() != mesh.triangles.size()) {
        return invalid_input(name + " are per corner but index " + str(att.corners.size()) +
                             " of " + str(mesh.triangles.size()) + " triangles");
      }
      for (size_t t = 0; t < att.corners.size(); ++t) {
        for (uint32_t i : att.corners[t]) {
          if (i >= att.value_count()) {
            return invalid_input(name + " of triangle " + str(t) + ": index " + str(i) +
                                 " out of range (" + str(att.value_count()) + " values)");
          }
        }
      }
    }
  }
  return Status::ok();
}

Result<std::unique_ptr<draco::Mesh>> to_draco_mesh(const TriangleMesh& mesh) {
  LODBAKE_RETURN_IF_ERROR(check_mesh_for_export(mesh));
  const bool per_corner = mesh.normals.binding == AttributeBinding::kPerCorner ||
                          mesh.texcoords.binding == AttributeBinding::kPerCorner;
  std::vector<uint32_t> point_vertex, point_normal, point_texcoord;
  std::vector<Triangle> faces;
  if (!per_corner) {
    point_vertex.resize(mesh.positions.size());
    for (size_t i = 0; i < point_vertex.size(); ++i)
      point_vertex[i] = static_cast<uint32_t>(i);
    point_normal = point_texcoord = point_vertex;
    faces = mesh.triangles;
  } else {
    std::vector<PointKey> keys;
    keys.reserve(mesh.triangles.size() * 3);
    std::vector<uint8_t> referenced(mesh.positions.size(), 0);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.triangles[t][k];
        referenced[v] = 1;
        keys.push_back(
            {v, corner_value(mesh.normals, mesh, t, k), corner_value(mesh.texcoords, mesh, t, k)});
      }
    }
    // Unreferenced vertices still become points, so export keeps them; their
    // per-corner attributes point at value 0 (any value would do).
    for (size_t v = 0; v < referenced.size(); ++v) {
      if (referenced[v]) continue;
      const uint32_t vi = static_cast<uint32_t>(v);
      keys.push_back({vi, mesh.normals.binding == AttributeBinding::kPerVertex ? vi : 0,
                      mesh.texcoords.binding == AttributeBinding::kPerVertex ? vi : 0});
    }
    std::vector<PointKey> points = keys;
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    faces.resize(mesh.triangles.size());
    for (size_t c = 0; c < mesh.triangles.size() * 3; ++c) {
      const auto it = std::lower_bound(points.begin(), points.end(), keys[c]);
      faces[c / 3][c % 3] = static_cast<uint32_t>(it - points.begin());
    }
    for (const PointKey& p : points) {
      point_vertex.push_back(p.vertex);
      point_normal.push_back(p.normal);
      point_texcoord.push_back(p.texcoord);
    }
  }
  auto out = std::make_unique<draco::Mesh>();
  out->set_num_points(static_cast<uint32_t>(point_vertex.size()));
  MeshAttribute positions;
  positions.binding = AttributeBinding::kPerVertex;
  positions.components = 3;
  positions.values.resize(mesh.positions.size() * 3);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    for (int k = 0; k < 3; ++k)
      positions.values[3 * v + k] = mesh.positions[v][k];
  }
  add_float_attribute(out.get(), draco::GeometryAttribute::POSITION, positions, 3, point_vertex);
  if (mesh.normals.present()) {
    add_float_attribute(out.get(), draco::GeometryAttribute::NORMAL, mesh.normals, 3, point_normal);
  }
  if (mesh.texcoords.present()) {
    add_float_attribute(out.get(), draco::GeometryAttribute::TEX_COORD, mesh.texcoords, 2,
                        point_texcoord);
  }
  for (const Triangle& t : faces) {
    out->AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  }
  return out;
}

}  // namespace dracoio
}  // namespace lodbake
