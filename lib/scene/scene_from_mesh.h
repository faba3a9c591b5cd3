// A TriangleMesh as a Scene: how every mesh file (OBJ, PLY, OFF, STL, .drc)
// becomes an asset, and how a tool holding a TriangleMesh hands it to the
// scene writers.
#pragma once

#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/status.h"

namespace lodbake {

/// One indexed triangle primitive (material -1) of `mesh`: POSITION, NORMAL
/// and TEXCOORD_0 as FLOAT streams, plus `vertex_streams` (each with one
/// element per mesh vertex, e.g. a PLY's COLOR_0), sorted by semantic.
/// Per-corner attributes split vertices: one glTF vertex per distinct
/// (position, normal, texture coordinate) index triple, numbered as
/// split_corner_attributes() numbers them (a vertex keeps its index for the
/// first triple met and the others are appended), so vertices no triangle
/// uses are kept. Texture v is flipped to glTF's top-left origin
/// (v' = 1 - v); normals are as given. Fails (kInvalidInput) on an index out
/// of range or an attribute whose size does not match its binding.
Result<ScenePrimitive> primitive_from_mesh(const TriangleMesh& mesh,
                                           const std::vector<SceneAttribute>& vertex_streams = {});

/// The Scene every mesh file gives: mesh 0 named `name` with `primitives`,
/// one node using it (no transform), one scene holding that node, default
/// scene 0.
Scene scene_of_mesh(std::string name, std::vector<ScenePrimitive> primitives);

/// scene_of_mesh(name, {primitive_from_mesh(mesh)}).
Result<Scene> scene_from_mesh(const TriangleMesh& mesh, const std::string& name);

/// `count` elements of `components` floats (1 to 4) as a FLOAT accessor.
AccessorData float_accessor(const float* values, uint32_t count, uint32_t components);

}  // namespace lodbake
