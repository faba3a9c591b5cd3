// What an importer tells its caller besides the mesh: notes about things it
// read but did not keep (so nothing is dropped silently; tools print them on
// stderr) and how the file's faces were turned into triangles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lodbake {

struct ImportReport {
  std::string format;                  // "obj", "ply-ascii", "ply-binary-le", "stl-binary", ...
  uint64_t file_faces = 0;             // faces as stored (polygons count once)
  uint64_t polygons_triangulated = 0;  // faces with more than 3 corners
  uint64_t welded_vertices = 0;        // corners merged by exact position (STL, glTF)
  std::vector<std::string> notes;      // one line each, e.g. "ignored vertex property 'confidence'"
  // Things the user must hear about although the read succeeded, one line
  // each, e.g. "image 2 'Lantern_baseColor.png' is missing".
  std::vector<std::string> warnings;
};

}  // namespace lodbake
