// Role and slot assignment for the PLY reader, plus the up-front size bound.
// Choices where PLY conventions vary:
// - Positions are `vertex` x y z of any scalar type (float and double are
//   the usual ones); normals need all of nx ny nz; texture coordinates are
//   the first complete pair of u v, s t, texture_u texture_v, texture_s
//   texture_t. Colours, when the caller wants them, are red green blue
//   [alpha] of one type among uchar, ushort, float and double (the types
//   glTF's COLOR_n can hold, double narrowed to float). Everything else
//   (confidence, intensity, colours of other types or not wanted, a partial
//   normal, a second texture pair, list properties) is skipped with a note.
// - Faces are the `face` element's vertex_indices list, or vertex_index as
//   older writers call it; strips are the `tristrips` element's
//   vertex_indices list. Index entries must have an integer type.
// - Any other element is skipped with a note.
// - A file with neither faces nor strips is a point cloud and is refused:
//   lodbake only bakes triangle meshes.
// The size bound counts the fewest bytes each item can take: binary, the
// sizes of its scalars and list lengths (a face list also needs 3 entries,
// since smaller faces are rejected); ASCII, two characters (a digit and a
// separator) per value, the last value of the file needing no separator.
#include "lib/meshio/ply_plan.h"

#include <string>

#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

std::string name_of(const std::string& name) {
  return quote_token(name);
}

void note_skipped(const PlyElement& element, size_t index, ImportReport* report) {
  const PlyProperty& p = element.properties[index];
  report->notes.push_back("ignored " + element.name + (p.is_list ? " list" : "") + " property " +
                          name_of(p.name));
}

int scalar_property(const PlyElement& element, const char* name) {
  int i = element.find(name);
  return i >= 0 && !element.properties[static_cast<size_t>(i)].is_list ? i : -1;
}

bool is_colour_type(PlyType type) {
  return type == PlyType::kUint8 || type == PlyType::kUint16 || type == PlyType::kFloat32 ||
         type == PlyType::kFloat64;
}

void plan_colours(const PlyElement& element, PlyElementPlan* plan, PlyPlan* out) {
  static const char* const kChannels[4] = {"red", "green", "blue", "alpha"};
  int found[4];
  for (int c = 0; c < 4; ++c)
    found[c] = scalar_property(element, kChannels[c]);
  if (found[0] < 0 || found[1] < 0 || found[2] < 0) return;
  const PlyType type = element.properties[static_cast<size_t>(found[0])].type;
  if (!is_colour_type(type)) return;
  uint32_t components = 3;
  for (int c = 1; c < 4; ++c) {
    if (found[c] < 0) continue;
    if (element.properties[static_cast<size_t>(found[c])].type != type) {
      if (c == 3) break;  // an alpha of another type is skipped alone
      return;
    }
    if (c == 3) components = 4;
  }
  for (uint32_t c = 0; c < components; ++c)
    plan->slots[static_cast<size_t>(found[c])] = static_cast<uint8_t>(kSlotRed + c);
  out->colour_components = components;
  out->colour_type = type;
}

Status plan_vertex(const PlyElement& element, PlyElementPlan* plan, PlyPlan* out,
                   bool want_colours) {
  static const char* const kAxes[3] = {"x", "y", "z"};
  for (uint8_t axis = 0; axis < 3; ++axis) {
    int i = element.find(kAxes[axis]);
    if (i < 0) {
      return invalid_input("element 'vertex' has no " + name_of(kAxes[axis]) + " property");
    }
    if (element.properties[static_cast<size_t>(i)].is_list) {
      return invalid_input("vertex property " + name_of(kAxes[axis]) + " is a list, not a number");
    }
    plan->slots[static_cast<size_t>(i)] = static_cast<uint8_t>(kSlotX + axis);
  }
  int nx = scalar_property(element, "nx");
  int ny = scalar_property(element, "ny");
  int nz = scalar_property(element, "nz");
  if (nx >= 0 && ny >= 0 && nz >= 0) {
    plan->slots[static_cast<size_t>(nx)] = kSlotNx;
    plan->slots[static_cast<size_t>(ny)] = kSlotNy;
    plan->slots[static_cast<size_t>(nz)] = kSlotNz;
    out->has_normals = true;
  }
  static const char* const kTexturePairs[4][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& pair : kTexturePairs) {
    int u = scalar_property(element, pair[0]);
    int v = scalar_property(element, pair[1]);
    if (u >= 0 && v >= 0) {
      plan->slots[static_cast<size_t>(u)] = kSlotU;
      plan->slots[static_cast<size_t>(v)] = kSlotV;
      out->has_texcoords = true;
      break;
    }
  }
  if (want_colours) plan_colours(element, plan, out);
  return Status::ok();
}

Status plan_index_list(const PlyElement& element, PlyElementPlan* plan) {
  int i = element.find("vertex_indices");
  if (i < 0 && element.name == "face") i = element.find("vertex_index");
  if (i < 0) {
    if (element.count == 0) return Status::ok();
    return invalid_input("element " + name_of(element.name) + " has no 'vertex_indices' list");
  }
  const PlyProperty& p = element.properties[static_cast<size_t>(i)];
  if (!p.is_list) {
    return invalid_input(element.name + " property " + name_of(p.name) +
                         " is a single value, not a list");
  }
  if (!ply_type_is_integer(p.type)) {
    return invalid_input(element.name + " list " + name_of(p.name) + " has " +
                         ply_type_name(p.type) + " entries; vertex indices must be integers");
  }
  plan->slots[static_cast<size_t>(i)] = kSlotIndices;
  return Status::ok();
}

uint64_t min_item_bytes(const PlyElementPlan& plan, bool binary) {
  uint64_t bytes = 0;
  const auto& properties = plan.element->properties;
  for (size_t k = 0; k < properties.size(); ++k) {
    const PlyProperty& p = properties[k];
    bytes += binary ? ply_type_size(p.is_list ? p.count_type : p.type) : 2;
    if (plan.role == PlyRole::kFace && plan.slots[k] == kSlotIndices) {
      bytes += 3 * (binary ? ply_type_size(p.type) : 2);
    }
  }
  return bytes;
}

Status check_body_size(const PlyPlan& plan, PlyFormat format, uint64_t body_size) {
  const bool binary = format != PlyFormat::kAscii;
  const uint64_t allowance = binary ? body_size : body_size + 1;
  uint64_t total = 0;
  for (const PlyElementPlan& e : plan.elements) {
    uint64_t need = 0;
    bool overflow = __builtin_mul_overflow(e.element->count, min_item_bytes(e, binary), &need) ||
                    __builtin_add_overflow(total, need, &total);
    if (overflow || total > allowance) {
      return invalid_input("the body ends after " + std::to_string(body_size) +
                           " bytes, but element " + name_of(e.element->name) + " declares " +
                           std::to_string(e.element->count) + " items, which need at least " +
                           (overflow ? std::string("2^64") : std::to_string(total)) +
                           (binary ? " bytes" : " bytes of text") + " up to its end");
    }
  }
  return Status::ok();
}

}  // namespace

Result<PlyPlan> plan_ply(const PlyHeader& header, uint64_t body_size, ImportReport* report,
                         bool want_colours) {
  PlyPlan plan;
  bool have_vertex = false;
  bool have_triangles = false;
  for (const PlyElement& element : header.elements) {
    PlyElementPlan e;
    e.element = &element;
    e.slots.assign(element.properties.size(), kSlotSkip);
    if (element.name == "vertex") {
      e.role = PlyRole::kVertex;
      LODBAKE_RETURN_IF_ERROR(plan_vertex(element, &e, &plan, want_colours));
      plan.vertex_count = element.count;
      have_vertex = true;
    } else if (element.name == "face" || element.name == "tristrips") {
      e.role = element.name == "face" ? PlyRole::kFace : PlyRole::kStrips;
      LODBAKE_RETURN_IF_ERROR(plan_index_list(element, &e));
      if (e.role == PlyRole::kFace) plan.face_count = element.count;
      have_triangles = true;
    } else {
      report->notes.push_back("skipped element " + name_of(element.name) + " (" +
                              std::to_string(element.count) + " items)");
    }
    if (e.role != PlyRole::kSkip) {
      for (size_t k = 0; k < e.slots.size(); ++k) {
        if (e.slots[k] == kSlotSkip) note_skipped(element, k, report);
      }
    }
    plan.elements.push_back(std::move(e));
  }
  if (!have_vertex) return invalid_input("no 'vertex' element");
  if (!have_triangles) {
    return invalid_input("no 'face' or 'tristrips' element: the file is a point cloud, not a mesh");
  }
  LODBAKE_RETURN_IF_ERROR(check_body_size(plan, header.format, body_size));
  if (plan.vertex_count > UINT32_MAX) {
    return invalid_input("element 'vertex' declares " + std::to_string(plan.vertex_count) +
                         " items; lodbake indexes at most " + std::to_string(UINT32_MAX) +
                         " vertices");
  }
  return plan;
}

}  // namespace lodbake
