// --validate's deep checks: besides each section's own validation
// (formats/sections/section_validation.h), what every consumer of a group's
// sections runs on them, from the base mesh to the finest mesh and back, so
// that a container --validate passes is one every replay mode, `lodbake-inspect
// --extract` and the tools that read a progressive mesh accept:
// - BASE + VSPL: the progressive mesh replayed split by split to the full
//   mesh and collapsed back (PmRefiner), and mapped to the input order;
// - BASE + VHIE + RFIN: mode vhier's SelectiveRefiner splits every node
//   (with its dependencies) to the leaves and collapses back to the roots,
//   the mesh checked at both ends; mode stream's server and client stream
//   every split (tolerance 0) and coarsen back;
// - + VTRE: mode vtrees' database over the hierarchy, and a session that
//   sends every split, the client's list and triangles the server's;
// - BASE + VSPL + DAGE: every dependency the progressive mesh's lineage
//   implies is in the DAG (so any front it allows is a valid mesh), and the
//   fronts split every node and collapse every one, the cut checked;
//   with VHIE too, the DAG's full cut is the hierarchy's;
// - BASE + FANH: the fan replay at the coarsest mesh, and the runtime
//   merging and splitting every node;
// - BASE + VSPL + SETS: the strip graph's recovery at the finest and the
//   coarsest LoD and at LoDs between (10%, linear), each checked against the
//   progressive mesh;
// - BASE + STRP: the strips' mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/sections/section_validation.h"

namespace lodbake {

/// validate_sections(), then for every group the deep checks of the
/// structures whose sections have no finding. Findings of a group other
/// than 0 start with "group N: ". Empty when every consumer accepts the file.
/// \pre `decoded` is an opened container's decoded() (codecs decoded).
std::vector<SectionFinding> validate_container(const Container& decoded);

/// The deep checks of one group alone (no group prefix), skipping the
/// structures that use a tag in `skip` (tags with findings already).
std::vector<SectionFinding> validate_group_structures(const Container& decoded, uint32_t group,
                                                      const std::vector<std::string>& skip = {});

}  // namespace lodbake
