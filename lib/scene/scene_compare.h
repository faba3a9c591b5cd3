// Scene equality that says where two scenes differ, for round-trip tests and
// tools that check an export against its input.
#pragma once

#include <string>

#include "formats/scene/scene.h"

namespace lodbake {

struct SceneCompareOptions {
  // False: images' uri and mime_type are not compared. How an image is
  // stored is the container's choice (a GLB embeds every image and must give
  // its media type; a .gltf names a file for an image that was embedded), so
  // a round trip across formats keeps an image's bytes, not its storage.
  bool image_storage = true;
};

// "" when `a` and `b` are equal (Scene::operator==, or with the options'
// exceptions), else one line naming the first difference, in the order
// asset, scenes, nodes, meshes, images, accessors, carried JSON, extension
// lists: "mesh 0 primitive 2 attribute TEXCOORD_0: element 8 component 1
// differs (0.25 vs 0.5)", "node 3 translation differs ([1,0,0] vs absent)",
// "materials differ at /0/name ("a" vs "b")".
std::string first_scene_difference(const Scene& a, const Scene& b,
                                   const SceneCompareOptions& options = {});

}  // namespace lodbake
