// Small meshes built in memory for the check and repair tests: the shapes of
// ../shared/data/bad/ (same coordinates and faces as the files) and a few
// regular ones whose counts are known in closed form.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {
namespace test_meshes {

inline TriangleMesh make(std::vector<Vec3f> positions, std::vector<Triangle> triangles) {
  TriangleMesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  return mesh;
}

// Closed, outward-wound (counter-clockwise seen from outside), genus 0.
inline TriangleMesh tetrahedron() {
  return make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
              {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

// Two triangles, one boundary loop of four edges.
inline TriangleMesh open_square() {
  return make({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

// bad/hw_nonmanifold_vertex_bowtie.off: two triangles meeting only at vertex 0.
inline TriangleMesh bowtie() {
  return make({{0, 0, 0}, {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 4, 3}});
}

// bad/hw_nonmanifold_vertex_two_cones.off: two closed capped hexagonal cones
// whose apexes are the same vertex 0.
inline TriangleMesh two_cones() {
  std::vector<Vec3f> p = {{0, 0, 0}};
  const float c = 0.866025f;
  const Vec3f ring[6] = {{1, 0, 0},  {0.5f, c, 0},   {-0.5f, c, 0},
                         {-1, 0, 0}, {-0.5f, -c, 0}, {0.5f, -c, 0}};
  for (float z : {1.0f, -1.0f}) {
    for (const Vec3f& r : ring)
      p.push_back({r[0], r[1], z});
    p.push_back({0, 0, z});
  }
  std::vector<Triangle> t;
  for (uint32_t i = 0; i < 6; ++i) {
    uint32_t a = 1 + i, b = 1 + (i + 1) % 6;  // upper ring, cap centre 7
    uint32_t d = 8 + i, e = 8 + (i + 1) % 6;  // lower ring, cap centre 14
    t.push_back({0, b, a});
    t.push_back({7, a, b});
    t.push_back({0, d, e});
    t.push_back({14, e, d});
  }
  return make(p, t);
}

// bad/hw_nonmanifold_edge_3tris.off shape: edge 0-1 shared by three triangles.
inline TriangleMesh three_on_an_edge() {
  return make({{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}},
              {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
}

// bad/draco_non_manifold_wrap.obj (0-based): edge 0-1 shared by four triangles.
inline TriangleMesh four_on_an_edge() {
  return make({{0, 0, 0},
               {1, 0, 0},
               {0.5f, 1, 0},
               {0.5f, -1, 0},
               {0.5f, 0, -1},
               {0.5f, 0, 1},
               {-0.5f, 0.2f, 0},
               {1.5f, 0.2f, 0},
               {-0.5f, -0.2f, 0},
               {1.5f, -0.2f, 0}},
              {{0, 1, 2},
               {0, 1, 4},
               {1, 0, 3},
               {1, 0, 5},
               {1, 5, 7},
               {1, 7, 2},
               {1, 3, 9},
               {1, 9, 4},
               {5, 0, 6},
               {6, 0, 2},
               {3, 0, 8},
               {8, 0, 4}});
}

// bad/hw_duplicate_faces.off: tetrahedron whose face (1 2 3) comes twice
// more, once with the same winding and once reversed.
inline TriangleMesh tetrahedron_with_duplicates() {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.push_back({1, 2, 3});
  mesh.triangles.push_back({3, 2, 1});
  return mesh;
}

// bad/hw_inconsistent_orientation.off: tetrahedron with face 2 flipped.
inline TriangleMesh tetrahedron_one_flipped() {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles[2] = {0, 2, 3};
  return mesh;
}

// bad/hw_degenerate_zero_area.off: unit square (faces 0, 1) plus (0 5 1)
// collinear, (1 2 2) repeated index, (0 4 3) with vertices 0 and 4 at the
// same position, (3 3 3).
inline TriangleMesh square_with_degenerates() {
  return make({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {0.5f, 0, 0}},
              {{0, 1, 2}, {0, 2, 3}, {0, 5, 1}, {1, 2, 2}, {0, 4, 3}, {3, 3, 3}});
}

// bad/hw_unreferenced_vertices.off: tetrahedron on vertices 0 1 3 4, plus 2,
// 5 and 6 that no face uses (6 far away).
inline TriangleMesh tetrahedron_with_unreferenced() {
  return make({{0, 0, 0},
               {1, 0, 0},
               {5, 5, 5},
               {0, 1, 0},
               {0, 0, 1},
               {0.25f, 0.25f, 0.25f},
               {1e6f, -1e6f, 1e6f}},
              {{0, 3, 1}, {0, 1, 4}, {0, 4, 3}, {1, 3, 4}});
}

// An nu x nv grid wrapped into a torus (major radius 2, minor 0.5), outward
// wound: 2 nu nv triangles, nu nv vertices, genus 1.
inline TriangleMesh torus(uint32_t nu, uint32_t nv) {
  TriangleMesh mesh;
  const double pi = 3.14159265358979323846;
  for (uint32_t i = 0; i < nu; ++i) {
    for (uint32_t j = 0; j < nv; ++j) {
      double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
      double r = 2 + 0.5 * std::cos(v);
      mesh.positions.push_back({static_cast<float>(r * std::cos(u)),
                                static_cast<float>(r * std::sin(u)),
                                static_cast<float>(0.5 * std::sin(v))});
    }
  }
  auto id = [&](uint32_t i, uint32_t j) { return (i % nu) * nv + (j % nv); };
  for (uint32_t i = 0; i < nu; ++i) {
    for (uint32_t j = 0; j < nv; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

// The torus grid glued with a flip (row i = nu meets row 0 at j -> -j): a
// closed Klein bottle, non-orientable, every vertex interior.
inline TriangleMesh klein_bottle(uint32_t nu, uint32_t nv) {
  TriangleMesh mesh = torus(nu, nv);
  mesh.triangles.clear();
  auto id = [&](uint32_t i, uint32_t j) { return i == nu ? (nv - j % nv) % nv : i * nv + j % nv; };
  for (uint32_t i = 0; i < nu; ++i) {
    for (uint32_t j = 0; j < nv; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

// A strip of n quads (2n triangles) along x whose far end is glued to the
// near end with a half twist: a Moebius band, every vertex on its boundary.
inline TriangleMesh moebius_band(uint32_t n) {
  TriangleMesh mesh;
  const double pi = 3.14159265358979323846;
  for (uint32_t i = 0; i < n; ++i) {
    double u = 2 * pi * i / n;
    for (double s : {-0.3, 0.3}) {
      double r = 1 + s * std::cos(u / 2);
      mesh.positions.push_back({static_cast<float>(r * std::cos(u)),
                                static_cast<float>(r * std::sin(u)),
                                static_cast<float>(s * std::sin(u / 2))});
    }
  }
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t a = 2 * i, b = 2 * i + 1;
    uint32_t c = i + 1 < n ? 2 * (i + 1) : 1;  // the twist swaps the sides
    uint32_t d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    mesh.triangles.push_back({a, c, d});
    mesh.triangles.push_back({a, d, b});
  }
  return mesh;
}

// Per-corner attribute with a distinct value per corner (corner k of
// triangle t gets value 3t + k), so tests can follow corners around.
inline MeshAttribute distinct_corner_attribute(size_t triangles, uint32_t components) {
  MeshAttribute attribute;
  attribute.binding = AttributeBinding::kPerCorner;
  attribute.components = components;
  for (size_t t = 0; t < triangles; ++t) {
    Triangle corners;
    for (uint32_t k = 0; k < 3; ++k) {
      corners[k] = static_cast<uint32_t>(3 * t + k);
      for (uint32_t c = 0; c < components; ++c) {
        attribute.values.push_back(static_cast<float>(3 * t + k) + 0.25f * static_cast<float>(c));
      }
    }
    attribute.corners.push_back(corners);
  }
  return attribute;
}

// Per-vertex attribute whose value for vertex v is (v, v + 0.5[, v + 0.25]).
inline MeshAttribute vertex_id_attribute(size_t vertices, uint32_t components) {
  MeshAttribute attribute;
  attribute.binding = AttributeBinding::kPerVertex;
  attribute.components = components;
  for (size_t v = 0; v < vertices; ++v) {
    for (uint32_t c = 0; c < components; ++c) {
      attribute.values.push_back(static_cast<float>(v) + (c == 1 ? 0.5f : c == 2 ? 0.25f : 0.0f));
    }
  }
  return attribute;
}

}  // namespace test_meshes
}  // namespace lodbake
