// KHR_draco_mesh_compression (KhronosGroup/glTF, extensions/2.0/Khronos/
// KHR_draco_mesh_compression) for the scene reader. The extension says the
// primitive's accessors describe the decoded data, so each stream takes the
// componentType, type and normalized flag of its accessor (BoxMetaDraco's
// feature ids stay UNSIGNED_BYTE / UNSIGNED_SHORT / FLOAT) and the count of
// Draco points; Draco's ConvertValue does the conversion and refuses values
// the declared type cannot hold. One vertex per Draco point, as the decoder
// gives them: nothing is welded or split.
#include "lib/dracoio/gltf_scene_draco.h"

#include <cstring>
#include <utility>

#include "draco/compression/decode.h"
#include "draco/core/decoder_buffer.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_header.h"
#include "lib/dracoio/gltf_accessor_data.h"
#include "lib/dracoio/gltf_accessors.h"

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

template <typename T>
bool convert_all(const draco::PointAttribute& att, uint32_t points, uint32_t components,
                 uint8_t* out) {
  T value[16];
  for (uint32_t p = 0; p < points; ++p) {
    if (!att.ConvertValue<T>(att.mapped_index(draco::PointIndex(p)),
                             static_cast<int8_t>(components), value)) {
      return false;
    }
    std::memcpy(out, value, sizeof(T) * components);
    out += sizeof(T) * components;
  }
  return true;
}

bool convert(const draco::PointAttribute& att, uint32_t points, AccessorData* data) {
  uint8_t* out = data->bytes.data();
  const uint32_t n = data->components();
  switch (data->component_type) {
    case ComponentType::kByte:
      return convert_all<int8_t>(att, points, n, out);
    case ComponentType::kUnsignedByte:
      return convert_all<uint8_t>(att, points, n, out);
    case ComponentType::kShort:
      return convert_all<int16_t>(att, points, n, out);
    case ComponentType::kUnsignedShort:
      return convert_all<uint16_t>(att, points, n, out);
    case ComponentType::kUnsignedInt:
      return convert_all<uint32_t>(att, points, n, out);
    case ComponentType::kFloat:
      return convert_all<float>(att, points, n, out);
  }
  return false;
}

}  // namespace

DracoPrimitiveDecoder::DracoPrimitiveDecoder() = default;
DracoPrimitiveDecoder::~DracoPrimitiveDecoder() = default;

Result<DracoStreams> DracoPrimitiveDecoder::decode(GltfDocument* doc, const Json& ext,
                                                   const Json& attributes,
                                                   const std::string& where) {
  const std::string ew = where + " KHR_draco_mesh_compression";
  if (!ext.is_object()) return invalid_input(ew + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t view,
                           member_uint(ext, "bufferView", UINT64_MAX, UINT32_MAX, ew));
  if (view == UINT64_MAX) return invalid_input(ew + " has no bufferView");
  LODBAKE_ASSIGN_OR_RETURN(const ByteSpan bytes,
                           buffer_view_bytes(*doc, static_cast<int64_t>(view), ew));
  LODBAKE_ASSIGN_OR_RETURN(const Json* ids, member_object(ext, "attributes", ew));
  if (ids == nullptr) return invalid_input(ew + " has no attributes");
  std::shared_ptr<const draco::Mesh>& mesh = meshes_[view];
  if (mesh == nullptr) {
    const Status header = check_draco_header(bytes.data, bytes.size);
    if (!header.is_ok()) return Status(header.kind(), ew + ": " + header.message());
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
      return invalid_input(ew + ": Draco decoding failed: " + decoded.status().error_msg_string());
    }
    mesh = std::shared_ptr<const draco::Mesh>(std::move(decoded).value());
  }
  const Status faces = check_faces(*mesh);
  if (!faces.is_ok()) return Status(faces.kind(), ew + ": " + faces.message());
  DracoStreams out;
  out.points = mesh->num_points();
  LODBAKE_RETURN_IF_ERROR(doc->budget.charge(uint64_t{mesh->num_faces()} * 12, ew));
  out.indices.resize(size_t{mesh->num_faces()} * 3);
  for (uint32_t f = 0; f < mesh->num_faces(); ++f) {
    const auto& face = mesh->face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k)
      out.indices[size_t{f} * 3 + static_cast<size_t>(k)] = face[k].value();
  }
  const size_t accessor_count = top_level_count(doc->root, "accessors");
  for (auto it = ids->begin(); it != ids->end(); ++it) {
    const std::string aw = ew + " " + it.key().substr(0, 100);
    const auto accessor = attributes.find(it.key());
    if (accessor == attributes.end()) {
      return invalid_input(aw + " is not an attribute of the primitive");
    }
    LODBAKE_ASSIGN_OR_RETURN(const int64_t accessor_index,
                             as_index(*accessor, accessor_count, "accessor", aw));
    LODBAKE_ASSIGN_OR_RETURN(AccessorData data, accessor_declaration(*doc, accessor_index));
    LODBAKE_ASSIGN_OR_RETURN(const int64_t id, as_index(it.value(), UINT32_MAX, "Draco id", aw));
    const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(id));
    if (att == nullptr) {
      return invalid_input(aw + ": attribute id " + str(static_cast<uint64_t>(id)) +
                           " is not in the Draco data");
    }
    if (att->num_components() != data.components()) {
      return invalid_input(aw + ": the Draco attribute has " + str(att->num_components()) +
                           " components, its accessor " + str(data.components()));
    }
    const Status mapping = check_mapping(*att, out.points);
    if (!mapping.is_ok()) return Status(mapping.kind(), aw + ": " + mapping.message());
    data.count = out.points;
    const uint64_t size = uint64_t{out.points} * data.element_size();
    LODBAKE_RETURN_IF_ERROR(doc->budget.charge(size, aw));
    data.bytes.resize(static_cast<size_t>(size));
    if (!convert(*att, out.points, &data)) {
      return invalid_input(aw + ": a Draco value does not fit the accessor's component type");
    }
    out.attributes.emplace(it.key(), std::move(data));
  }
  return out;
}

}  // namespace dracoio
}  // namespace lodbake
