// Sections are decoded in one pass, then the cross-section checks run, so
// the result does not depend on the order of the sections in the file (a
// VSPL may precede its BASE).
#include "formats/sections/section_validation.h"

#include <optional>
#include <string>
#include <utility>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/scne.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/sections/wedg.h"

namespace lodbake {
namespace {

// What the cross-section checks know of each section.
struct Decoded {
  std::optional<MetaSection> meta;
  const Section* base_section = nullptr;
  std::optional<BaseSummary> base;        // its fixed fields read
  std::optional<TriangleMesh> base_mesh;  // decoded in full
  const Section* vspl_section = nullptr;
  std::optional<VsplSummary> vspl;         // its fixed fields read
  std::optional<uint64_t> full_triangles;  // when VSPL decoded in full
  const Section* dage_section = nullptr;
  const Section* vtre_section = nullptr;
  const Section* vhie_section = nullptr;
  const Section* rfin_section = nullptr;
  const Section* fanh_section = nullptr;
  std::optional<TriangleMesh> fanh_base;  // BASE's mesh, kept for FANH's replay
  const Section* strp_section = nullptr;
  const Section* sets_section = nullptr;
  const Section* wedg_section = nullptr;
  std::optional<ProgressiveMesh> pm;  // kept from VSPL's check when WEDG needs it
};

// META's counts, when present, must agree with the sections they describe
// (docs/format.md "META": vertices and triangles describe BASE; splits,
// full_vertices and full_triangles a progressive mesh's BASE + VSPL).
void check_meta_counts(const Decoded& d, std::vector<SectionFinding>* findings) {
  const MetaSection& meta = *d.meta;
  auto expect = [&](const char* key, uint64_t actual, const char* holder) {
    auto it = meta.counts.find(key);
    if (it != meta.counts.end() && it->second != actual) {
      findings->push_back({kMetaTag, std::string("counts.") + key + " is " +
                                         std::to_string(it->second) + " but " + holder + " " +
                                         std::to_string(actual)});
    }
  };
  if (d.base) {
    expect("vertices", d.base->vertex_count, "BASE holds");
    expect("triangles", d.base->triangle_count, "BASE holds");
  }
  if (d.vspl) {
    expect("splits", d.vspl->split_count, "VSPL holds");
    expect("full_vertices", d.vspl->full_vertex_count(), "BASE and VSPL make");
    if (d.full_triangles) expect("full_triangles", *d.full_triangles, "BASE and VSPL make");
  } else if (d.vspl_section == nullptr) {
    for (const char* key : {"splits", "full_vertices", "full_triangles"}) {
      if (meta.counts.count(key) != 0) {
        findings->push_back(
            {kMetaTag, std::string("counts.") + key + " is given but there is no VSPL section"});
      }
    }
  }
}

// VSPL needs its base mesh: the vertex counts must agree, the records are
// decoded against BASE's positions, and the attributes must be in both or
// in neither (join_progressive_mesh()).
void check_vspl(Decoded* d, std::vector<SectionFinding>* findings) {
  const Section& section = *d->vspl_section;
  Result<VsplSummary> summary = read_vspl_summary(section.data, section.size);
  if (!summary.is_ok()) {
    findings->push_back({kVsplTag, summary.status().message()});
    return;
  }
  d->vspl = summary.value();
  if (d->base_section == nullptr) {
    findings->push_back({kVsplTag, "no BASE section holds the base mesh of the " +
                                       std::to_string(d->vspl->split_count) + " splits"});
    return;
  }
  if (d->base && d->base->vertex_count != d->vspl->base_vertex_count) {
    findings->push_back(
        {kVsplTag, "base vertex count " + std::to_string(d->vspl->base_vertex_count) +
                       " but BASE holds " + std::to_string(d->base->vertex_count) + " vertices"});
    return;
  }
  if (!d->base_mesh) return;  // BASE's own finding says why
  Result<VsplSection> decoded = decode_vspl(section.data, section.size, d->base_mesh->positions);
  if (!decoded.is_ok()) {
    findings->push_back({kVsplTag, decoded.status().message()});
    return;
  }
  const uint64_t base_triangles = d->base_mesh->triangle_count();
  d->full_triangles = full_triangle_count(base_triangles, decoded.value().splits);
  Result<ProgressiveMesh> pm =
      join_progressive_mesh(std::move(*d->base_mesh), std::move(decoded).value());
  d->base_mesh.reset();
  if (!pm.is_ok()) {
    findings->push_back({kVsplTag, pm.status().message()});
    return;
  }
  for (std::string& finding : validate_vspl(pm.value()))
    findings->push_back({kVsplTag, std::move(finding)});
  if (d->wedg_section != nullptr) d->pm = std::move(pm).value();
}

// WEDG follows the group's progressive mesh, or BASE without one.
void check_wedg(const Decoded& d, std::vector<SectionFinding>* findings) {
  Result<PmWedges> wedges = decode_wedg(d.wedg_section->data, d.wedg_section->size);
  if (!wedges.is_ok()) {
    findings->push_back({kWedgTag, wedges.status().message()});
    return;
  }
  if (d.vspl_section == nullptr) {
    // Without a progressive mesh, WEDG gives BASE's own corners (a fan
    // hierarchy's input).
    if (d.base_section == nullptr) {
      findings->push_back({kWedgTag, "no BASE or VSPL section holds the mesh it describes"});
      return;
    }
    if (!d.base_mesh) return;  // BASE's own finding says why
    for (std::string& finding : validate_wedg_corners(wedges.value(), *d.base_mesh))
      findings->push_back({kWedgTag, std::move(finding)});
    return;
  }
  if (!d.pm) return;  // VSPL's own finding says why
  for (std::string& finding : validate_wedg(wedges.value(), *d.pm))
    findings->push_back({kWedgTag, std::move(finding)});
}

// DAGE and VTRE describe the container's progressive mesh: one DAG node,
// and one pair of tree children, per VSPL record over BASE's vertices.
void check_split_counts(const char* tag, uint64_t splits, uint64_t base_vertices, const Decoded& d,
                        std::vector<SectionFinding>* findings) {
  if (d.vspl_section == nullptr) {
    findings->push_back(
        {tag, "no VSPL section holds the " + std::to_string(splits) + " splits it describes"});
  }
  if (d.vspl && d.vspl->split_count != splits) {
    findings->push_back({tag, "holds " + std::to_string(splits) + " splits but VSPL holds " +
                                  std::to_string(d.vspl->split_count)});
  }
  if (d.base && d.base->vertex_count != base_vertices) {
    findings->push_back({tag, "base vertex count " + std::to_string(base_vertices) +
                                  " but BASE holds " + std::to_string(d.base->vertex_count) +
                                  " vertices"});
  }
}

void check_dage(const Decoded& d, std::vector<SectionFinding>* findings) {
  DageSummary summary;
  Result<VsplitDag> dag = decode_dage(d.dage_section->data, d.dage_section->size, &summary);
  if (!dag.is_ok()) {
    findings->push_back({kDageTag, dag.status().message()});
    return;
  }
  for (std::string& finding : validate_dage(dag.value()))
    findings->push_back({kDageTag, std::move(finding)});
  check_split_counts(kDageTag, summary.node_count, summary.base_vertex_count, d, findings);
}

void check_vtre(const Decoded& d, std::vector<SectionFinding>* findings) {
  VtreSummary summary;
  Result<VertexTrees> trees = decode_vtre(d.vtre_section->data, d.vtre_section->size, &summary);
  if (!trees.is_ok()) {
    findings->push_back({kVtreTag, trees.status().message()});
    return;
  }
  for (std::string& finding : validate_vtre(trees.value()))
    findings->push_back({kVtreTag, std::move(finding)});
  check_split_counts(kVtreTag, summary.split_count, summary.base_vertex_count, d, findings);
}

// VHIE decodes onto BASE (its roots are BASE's vertices) and passes the
// hierarchy's structural checks; RFIN needs VHIE's splits. META's
// hierarchy counts must match.
void check_vhie(const Decoded& d, std::vector<SectionFinding>* findings) {
  if (d.vhie_section == nullptr) {
    if (d.rfin_section != nullptr) {
      findings->push_back({kRfinTag, "no VHIE section holds the hierarchy RFIN refers to"});
    }
    return;
  }
  const Section& section = *d.vhie_section;
  Result<VhieSummary> summary = read_vhie_summary(section.data, section.size);
  if (!summary.is_ok()) {
    findings->push_back({kVhieTag, summary.status().message()});
    return;
  }
  if (!d.base_mesh) {
    findings->push_back({kVhieTag, "no decodable BASE section holds the " +
                                       std::to_string(summary.value().root_count) + " roots"});
    return;
  }
  Result<VertexHierarchy> h = decode_vhie(section.data, section.size, *d.base_mesh);
  if (!h.is_ok()) {
    findings->push_back({kVhieTag, h.status().message()});
    return;
  }
  if (d.meta) {
    const HierarchyShape shape = hierarchy_shape(h.value());
    for (const auto& [key, actual] : {std::make_pair("hierarchy_nodes", shape.nodes),
                                      std::make_pair("hierarchy_depth", uint64_t{shape.depth}),
                                      std::make_pair("input_vertices", shape.leaves)}) {
      auto it = d.meta->counts.find(key);
      if (it != d.meta->counts.end() && it->second != actual) {
        findings->push_back({kMetaTag, std::string("counts.") + key + " is " +
                                           std::to_string(it->second) + " but VHIE has " +
                                           std::to_string(actual)});
      }
    }
  }
  if (d.rfin_section == nullptr) return;
  Result<std::vector<NodeRefinement>> rfin =
      decode_rfin(d.rfin_section->data, d.rfin_section->size, h.value());
  if (!rfin.is_ok()) findings->push_back({kRfinTag, rfin.status().message()});
}

// FANH is a hierarchy over BASE's mesh: its lists are replayed over it.
void check_fanh(const Decoded& d, std::vector<SectionFinding>* findings) {
  const Section& section = *d.fanh_section;
  if (d.base_section == nullptr) {
    findings->push_back({kFanhTag, "no BASE section holds the mesh the hierarchy refers to"});
    return;
  }
  Result<FanHierarchy> h = decode_fanh(section.data, section.size);
  if (!h.is_ok()) {
    findings->push_back({kFanhTag, h.status().message()});
    return;
  }
  if (!d.fanh_base) {
    for (std::string& finding : validate_fanh_structure(h.value()))
      findings->push_back({kFanhTag, std::move(finding)});
    return;  // BASE's own finding says why the replay cannot run
  }
  for (std::string& finding : validate_fanh(h.value(), *d.fanh_base))
    findings->push_back({kFanhTag, std::move(finding)});
}

// The findings of one group's sections (tags unique).
std::vector<SectionFinding> validate_group(const Container& container) {
  std::vector<SectionFinding> findings;
  Decoded d;
  for (const Section& section : container.sections) {
    if (section.tag() == kMetaTag) {
      Result<MetaSection> decoded = decode_meta(section.data, section.size);
      if (decoded.is_ok()) {
        d.meta = std::move(decoded).value();
      } else {
        findings.push_back({kMetaTag, decoded.status().message()});
      }
    } else if (section.tag() == kBaseTag) {
      d.base_section = &section;
      BaseSummary summary;
      Result<TriangleMesh> mesh = decode_base(section.data, section.size, &summary);
      if (mesh.is_ok()) {
        for (std::string& finding : validate_base(mesh.value()))
          findings.push_back({kBaseTag, std::move(finding)});
        d.base = summary;
        d.base_mesh = std::move(mesh).value();
      } else {
        findings.push_back({kBaseTag, mesh.status().message()});
        Result<BaseSummary> fixed = read_base_summary(section.data, section.size);
        if (fixed.is_ok()) d.base = fixed.value();
      }
    } else if (section.tag() == kVsplTag) {
      d.vspl_section = &section;
    } else if (section.tag() == kDageTag) {
      d.dage_section = &section;
    } else if (section.tag() == kVtreTag) {
      d.vtre_section = &section;
    } else if (section.tag() == kVhieTag) {
      d.vhie_section = &section;
    } else if (section.tag() == kRfinTag) {
      d.rfin_section = &section;
    } else if (section.tag() == kFanhTag) {
      d.fanh_section = &section;
    } else if (section.tag() == kStrpTag) {
      d.strp_section = &section;
    } else if (section.tag() == kSetsTag) {
      d.sets_section = &section;
    } else if (section.tag() == kWedgTag) {
      d.wedg_section = &section;
    }
  }
  check_vhie(d, &findings);
  if (d.fanh_section != nullptr && d.base_mesh) d.fanh_base = *d.base_mesh;
  if (d.fanh_section != nullptr) check_fanh(d, &findings);
  // STRP indexes BASE's vertices; checked before VSPL takes the base mesh.
  if (d.strp_section != nullptr) {
    for (std::string& finding :
         validate_strp_payload(d.strp_section->data, d.strp_section->size,
                               d.base_section != nullptr, d.base_mesh ? &*d.base_mesh : nullptr))
      findings.push_back({kStrpTag, std::move(finding)});
  }
  if (d.vspl_section != nullptr) check_vspl(&d, &findings);
  if (d.dage_section != nullptr) check_dage(d, &findings);
  if (d.vtre_section != nullptr) check_vtre(d, &findings);
  if (d.sets_section != nullptr) {
    for (std::string& finding :
         validate_sets_payload(d.sets_section->data, d.sets_section->size,
                               d.vspl_section != nullptr, d.vspl ? &*d.vspl : nullptr))
      findings.push_back({kSetsTag, std::move(finding)});
  }
  if (d.wedg_section != nullptr) check_wedg(d, &findings);
  if (d.meta) check_meta_counts(d, &findings);
  return findings;
}

}  // namespace

std::vector<SectionFinding> validate_group_sections(const Container& container) {
  if (container.group_count() <= 1) return validate_group(container);
  std::vector<SectionFinding> findings;
  for (uint32_t group = 0; group < container.group_count(); ++group) {
    for (SectionFinding& f : validate_group(single_group(container, group))) {
      if (group != 0) f.message = "group " + std::to_string(group) + ": " + f.message;
      findings.push_back(std::move(f));
    }
  }
  return findings;
}

// SCNE names the group of each scene mesh: that group must hold a BASE.
std::vector<SectionFinding> validate_scene_map(const Container& container) {
  std::vector<SectionFinding> findings;
  const Section* scne = container.find(kScneTag, 0);
  if (scne == nullptr) return findings;
  Result<SceneSection> scene = decode_scne(scne->data, scne->size);
  if (!scene.is_ok()) {
    findings.push_back({kScneTag, scene.status().message()});
    return findings;
  }
  for (const SceneMeshGroup& m : scene.value().meshes) {
    if (container.find(kBaseTag, m.group) == nullptr)
      findings.push_back({kScneTag, "mesh " + std::to_string(m.mesh) + "'s group " +
                                        std::to_string(m.group) + " has no BASE section"});
  }
  return findings;
}

std::vector<SectionFinding> validate_sections(const Container& container) {
  std::vector<SectionFinding> findings = validate_group_sections(container);
  for (SectionFinding& f : validate_scene_map(container))
    findings.push_back(std::move(f));
  return findings;
}

}  // namespace lodbake
