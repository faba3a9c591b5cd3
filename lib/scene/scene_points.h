// Which vertices of a mesh's primitives are the same point.
#pragma once

#include "formats/scene/scene.h"

namespace lodbake {

// Fills mesh->point_of_vertex and mesh->point_count: two vertices (of the
// same or different primitives) are one point exactly when their POSITION
// elements are bit-for-bit equal (same component type, normalization and
// bytes). Points are numbered in first-seen order over primitives, then
// vertices. A primitive without POSITION has no vertices here. In
// lodbake_scene_flatten, which every scene reader links.
void weld_mesh_points(SceneMesh* mesh);

}  // namespace lodbake
