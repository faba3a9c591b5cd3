// The registry is a fixed list rather than a self-registration scheme so
// that what a build accepts is visible in one place and independent of link
// order.
//
// Required flags: only BASE is required. Every other section adds to the
// mesh in BASE (a finer mesh, a hierarchy, strips over its vertices,
// provenance) without changing what BASE is, so a reader that skips it still
// reads a correct mesh: the coarse base of a progressive mesh or hierarchy,
// or the full mesh under FANH and STRP. docs/format.md section 4 gives the
// reason per tag.
#include "formats/container/section_registry.h"

namespace lodbake {

const std::vector<SectionKind>& known_section_kinds() {
  static const std::vector<SectionKind> kinds = {
      {kMetaTag, "provenance: tool, version, options, input, counts (JSON)", false},
      {kBaseTag, "base triangle mesh: positions, triangles, normals, texture coordinates", true},
      {kVsplTag, "progressive mesh: vertex-split records and the input vertex permutation", false},
      {kDageTag, "DAG of vertex splits: each split's parent splits (Zheng & Chan)", false},
      {kVtreTag,
       "vertex trees: base, left and right node records with vertex fans (To, Lau & Green)", false},
      {kVhieTag, "balanced vertex hierarchy: trees, fundamental cut vertices, split positions",
       false},
      {kRfinTag, "refinement data per split: sphere, normal cone, screen-space error terms", false},
      {kFanhTag, "fan-merge hierarchy: nodes, fine-path children, modified and removed triangles",
       false},
      {kStrpTag, "triangle strips over BASE's vertices", false},
      {kSetsTag, "SETS multiresolution strip graph over a progressive mesh's contractions", false},
      {kScneTag, "the asset: glTF scene (nodes, materials, textures, skins) and its meshes' groups",
       false},
      {kWedgTag, "the wedges of an asset mesh's progressive mesh: each corner's primitive vertex",
       false},
  };
  return kinds;
}

bool is_known_section(std::string_view tag) {
  return section_description(tag) != nullptr;
}

const char* section_description(std::string_view tag) {
  for (const SectionKind& kind : known_section_kinds()) {
    if (tag == kind.tag) return kind.description;
  }
  return nullptr;
}

bool section_required(std::string_view tag) {
  for (const SectionKind& kind : known_section_kinds()) {
    if (tag == kind.tag) return kind.required;
  }
  return false;
}

}  // namespace lodbake
