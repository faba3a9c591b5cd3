// A scene (formats/scene/scene.h) merged into one TriangleMesh: what the
// mesh tools take from a glTF asset (parse_gltf() is read_gltf_scene() then
// this). Works on memory only and throws nothing.
#pragma once

#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

// All triangle primitives of the default scene (scene 0 without a default,
// every root node without scenes), node transforms applied, merged into one
// mesh in traversal order: roots in the scene's order, each subtree
// depth-first in `children` order, each mesh's primitives in order.
// - TRIANGLE_STRIP and TRIANGLE_FAN are unrolled as primitive_triangles()
//   does; POINTS and LINE* primitives and primitives without POSITION are
//   skipped with a note.
// - Positions are transformed in double precision, normals by the inverse
//   transpose and renormalized; an identity transform leaves values
//   bit-exact; a mirroring transform reverses the winding.
// - NORMAL and TEXCOORD_0 are kept when every triangle primitive has them
//   (else dropped with a note); texture v is flipped to v' = 1 - v (lodbake
//   puts the texture origin bottom-left, glTF top-left).
// - Welding as weld_vertices() (mesh_weld.h): every exactly equal position,
//   except a scene whose asset.extras.lodbake_weld is "none" or
//   "manifold_edges" (lodbake's GLB writer marks its files so).
// - Instancing can multiply geometry: decoded and instanced vertices plus
//   triangles are capped at `budget` (kInvalidInput beyond).
// - A required extension that changes geometry the flattening ignores
//   (EXT_mesh_gpu_instancing) fails with kUnsupported naming it.
// Everything else (materials, other attributes, morph targets, other
// scenes, extensions) is left out with one note each in report->notes;
// report->file_faces and report->welded_vertices are set, report->format is
// left to the reader.
Result<TriangleMesh> flatten_scene(const Scene& scene, uint64_t budget, ImportReport* report);

}  // namespace lodbake
