// Deep validation of a container's sections: decode every known section,
// run its validator, and check what sections say about each other (META's
// counts against BASE and VSPL, VSPL's base vertex count against BASE).
// What `lodbake-inspect --validate` runs.
#pragma once

#include <string>
#include <vector>

#include "formats/container/container_reader.h"

namespace lodbake {

struct SectionFinding {
  std::string tag;      // the section it concerns
  std::string message;  // one line
};

// Every finding: META's and BASE's own in section order, then FANH's
// (replayed over BASE), then VSPL's
// (decoded against BASE), then the META count checks; empty when all is well.
// \pre `container` passed read_container() and its buffer is alive.
// Also runs validate_scene_map().
std::vector<SectionFinding> validate_sections(const Container& container);

// validate_sections() without the scene map: for one group taken out of a
// container (single_group()), whose SCNE names groups that are not in it.
std::vector<SectionFinding> validate_group_sections(const Container& container);

// SCNE's map against the whole container: every mesh's group holds a BASE.
std::vector<SectionFinding> validate_scene_map(const Container& container);

}  // namespace lodbake
