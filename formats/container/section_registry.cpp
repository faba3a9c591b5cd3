// The registry is a fixed list rather than a self-registration scheme so
// that what a build accepts is visible in one place and independent of link
// order.
#include "formats/container/section_registry.h"

namespace lodbake {

const std::vector<SectionKind>& known_section_kinds() {
  static const std::vector<SectionKind> kinds = {
      {kMetaTag, "provenance: tool, version, options, input, counts (JSON)"},
      {kBaseTag, "base triangle mesh: positions, triangles, normals, texture coordinates"},
      {kVsplTag, "progressive mesh: vertex-split records and the input vertex permutation"},
      {kDageTag, "DAG of vertex splits: each split's parent splits (Zheng & Chan)"},
      {kVtreTag,
       "vertex trees: base, left and right node records with vertex fans (To, Lau & Green)"},
      {kVhieTag, "balanced vertex hierarchy: trees, fundamental cut vertices, split positions"},
      {kRfinTag, "refinement data per split: sphere, normal cone, screen-space error terms"},
      {kFanhTag, "fan-merge hierarchy: nodes, fine-path children, modified and removed triangles"},
      {kStrpTag, "triangle strips over BASE's vertices"},
      {kSetsTag, "SETS multiresolution strip graph over a progressive mesh's contractions"},
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

}  // namespace lodbake
