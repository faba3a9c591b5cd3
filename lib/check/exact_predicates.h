// Exact geometric predicates on float32 positions. The mesh check and the
// repair must agree on which triangles have zero area, whatever the
// coordinates, so the decision is exact rather than epsilon-based.
#pragma once

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

/// True when the triangle (a, b, c) has exactly zero area, i.e. the three
/// points are collinear (two or three coincident points included).
/// Exact for every finite float input: a floating-point filter decides the
/// common case, an exact expansion sum the rest.
/// \pre every coordinate is finite.
bool is_zero_area_triangle(const Vec3f& a, const Vec3f& b, const Vec3f& c);

}  // namespace lodbake
