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
std::vector<SectionFinding> validate_sections(const Container& container);

}  // namespace lodbake
