// What the PLY reader does with each element and property of a parsed
// header: which values become positions, normals, texture coordinates and
// triangles, and which are skipped (with a note). Also checks, before the
// reader allocates anything, that the body is large enough for every
// element the header declares.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/meshio/ply_header.h"

namespace lodbake {

enum class PlyRole : uint8_t { kVertex, kFace, kStrips, kSkip };

// Destination of one property's values. Vertex slots index a float[kVertexSlots].
enum PlySlot : uint8_t {
  kSlotX,
  kSlotY,
  kSlotZ,
  kSlotNx,
  kSlotNy,
  kSlotNz,
  kSlotU,
  kSlotV,
  kSlotRed,
  kSlotGreen,
  kSlotBlue,
  kSlotAlpha,
  kVertexSlots,
  kSlotSkip = 0xfe,     // read (validated) and dropped
  kSlotIndices = 0xff,  // the face or strip vertex index list
};

struct PlyElementPlan {
  const PlyElement* element = nullptr;  // points into the PlyHeader
  PlyRole role = PlyRole::kSkip;
  std::vector<uint8_t> slots;  // one PlySlot per property
};

struct PlyPlan {
  std::vector<PlyElementPlan> elements;  // in file order
  uint64_t vertex_count = 0;
  uint64_t face_count = 0;  // items of the 'face' element (a reservation hint)
  bool has_normals = false;
  bool has_texcoords = false;
  // Vertex colours, planned only when asked for: 0, 3 (red green blue) or 4
  // (with alpha) components, all of `colour_type`.
  uint32_t colour_components = 0;
  PlyType colour_type = PlyType::kUint8;
};

/// Decides each element's role and each property's slot, appends one note to
/// `report` per ignored property or skipped element, and checks that the
/// `body_size` bytes after the header can hold the smallest body the header
/// allows. Colours are read only when `want_colours` (otherwise skipped
/// with a note like any other property). Fails on a missing vertex element
/// or x/y/z property, on a mesh
/// without a face or tristrips element, on index lists of the wrong kind,
/// and on counts the body cannot hold.
Result<PlyPlan> plan_ply(const PlyHeader& header, uint64_t body_size, ImportReport* report,
                         bool want_colours = false);

}  // namespace lodbake
