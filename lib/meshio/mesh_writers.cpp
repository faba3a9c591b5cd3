// OBJ and OFF writers, the consistency check every writer runs first, and
// drops_attributes(). (PLY is in ply_writer.cpp.)
//
// Choices:
// - Floats are printed with std::to_chars' shortest round-trip form, so
//   reading the file back (parse_obj, parse_off) gives bit-identical floats.
// - OBJ keeps the attributes' bindings: per-vertex values are written in
//   vertex order and faces use the vertex index for them ("f 1/1/1"),
//   per-corner values in their own order with their own indices.
// - OFF writes per-vertex normals and texture coordinates in its NOFF, STOFF
//   or STNOFF variants; per-corner attributes have no OFF form and are left
//   out (drops_attributes() tells the caller, who warns).
// - No timestamps or version strings: the same mesh gives the same bytes.
#include <algorithm>
#include <cctype>
#include <limits>
#include <string>

#include "lib/meshio/mesh_writers.h"
#include "lib/meshio/writer_support.h"

namespace lodbake {
namespace {

Status check_attribute(const TriangleMesh& mesh, const MeshAttribute& a, uint32_t components,
                       const char* name) {
  if (!a.present()) return Status::ok();
  if (a.components != components || a.values.size() % components != 0) {
    return invalid_input(std::string("mesh ") + name + " have " + std::to_string(a.components) +
                         " components and " + std::to_string(a.values.size()) +
                         " floats; expected " + std::to_string(components) + " per value");
  }
  const size_t values = a.value_count();
  if (a.binding == AttributeBinding::kPerVertex) {
    if (values != mesh.positions.size()) {
      return invalid_input(std::string("mesh has ") + std::to_string(mesh.positions.size()) +
                           " vertices but " + std::to_string(values) + " per-vertex " + name);
    }
    return Status::ok();
  }
  if (a.corners.size() != mesh.triangles.size()) {
    return invalid_input(std::string("mesh has ") + std::to_string(mesh.triangles.size()) +
                         " triangles but " + std::to_string(a.corners.size()) + " " + name +
                         " corner triples");
  }
  for (size_t t = 0; t < a.corners.size(); ++t) {
    for (uint32_t i : a.corners[t]) {
      if (i >= values) {
        return invalid_input(std::string("triangle ") + std::to_string(t) + " uses " + name +
                             " value " + std::to_string(i) + " of " + std::to_string(values));
      }
    }
  }
  return Status::ok();
}

// Index of corner k of triangle t into the attribute's values.
uint32_t value_index(const MeshAttribute& a, const TriangleMesh& mesh, size_t t, int k) {
  return a.binding == AttributeBinding::kPerCorner ? a.corners[t][k] : mesh.triangles[t][k];
}

std::string lower_extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

Status check_writable(const TriangleMesh& mesh) {
  if (mesh.positions.size() >= std::numeric_limits<uint32_t>::max())
    return invalid_input("mesh has more vertices than 32-bit indices can address");
  const size_t v = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t i : mesh.triangles[t]) {
      if (i >= v) {
        return invalid_input("triangle " + std::to_string(t) + " uses vertex " + std::to_string(i) +
                             " of " + std::to_string(v));
      }
    }
  }
  LODBAKE_RETURN_IF_ERROR(check_attribute(mesh, mesh.normals, 3, "normals"));
  LODBAKE_RETURN_IF_ERROR(check_attribute(mesh, mesh.texcoords, 2, "texture coordinates"));
  return Status::ok();
}

Result<Bytes> write_obj(const TriangleMesh& mesh) {
  LODBAKE_RETURN_IF_ERROR(check_writable(mesh));
  Bytes bytes;
  TextOut out(&bytes);
  out.text("# written by lodbake\n");
  for (const Vec3f& p : mesh.positions) {
    out.text("v ");
    out.reals(p.data(), 3);
    out.ch('\n');
  }
  const std::vector<float>& uv = mesh.texcoords.values;
  for (size_t i = 0; mesh.texcoords.present() && i + 1 < uv.size(); i += 2) {
    out.text("vt ");
    out.reals(&uv[i], 2);
    out.ch('\n');
  }
  const std::vector<float>& n = mesh.normals.values;
  for (size_t i = 0; mesh.normals.present() && i + 2 < n.size(); i += 3) {
    out.text("vn ");
    out.reals(&n[i], 3);
    out.ch('\n');
  }
  const bool has_uv = mesh.texcoords.present();
  const bool has_n = mesh.normals.present();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    out.ch('f');
    for (int k = 0; k < 3; ++k) {
      out.ch(' ');
      out.integer(uint64_t{mesh.triangles[t][k]} + 1);
      if (!has_uv && !has_n) continue;
      out.ch('/');
      if (has_uv) out.integer(uint64_t{value_index(mesh.texcoords, mesh, t, k)} + 1);
      if (has_n) {
        out.ch('/');
        out.integer(uint64_t{value_index(mesh.normals, mesh, t, k)} + 1);
      }
    }
    out.ch('\n');
  }
  return bytes;
}

Result<Bytes> write_off(const TriangleMesh& mesh) {
  LODBAKE_RETURN_IF_ERROR(check_writable(mesh));
  const bool st = mesh.texcoords.binding == AttributeBinding::kPerVertex;
  const bool normals = mesh.normals.binding == AttributeBinding::kPerVertex;
  Bytes bytes;
  TextOut out(&bytes);
  std::string keyword = std::string(st ? "ST" : "") + (normals ? "N" : "") + "OFF\n";
  out.text(keyword);
  out.integer(mesh.positions.size());
  out.ch(' ');
  out.integer(mesh.triangles.size());
  out.text(" 0\n");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    out.reals(mesh.positions[i].data(), 3);
    if (normals) {
      out.ch(' ');
      out.reals(&mesh.normals.values[i * 3], 3);
    }
    if (st) {
      out.ch(' ');
      out.reals(&mesh.texcoords.values[i * 2], 2);
    }
    out.ch('\n');
  }
  for (const Triangle& t : mesh.triangles) {
    out.ch('3');
    for (uint32_t i : t) {
      out.ch(' ');
      out.integer(i);
    }
    out.ch('\n');
  }
  return bytes;
}

bool drops_attributes(const std::string& path, const TriangleMesh& mesh) {
  const std::string ext = lower_extension(path);
  if (ext == ".off") {
    return mesh.normals.binding == AttributeBinding::kPerCorner ||
           mesh.texcoords.binding == AttributeBinding::kPerCorner;
  }
  // OBJ keeps both bindings; PLY and GLB split per-corner values into
  // per-vertex ones by duplicating vertices.
  return false;
}

}  // namespace lodbake
