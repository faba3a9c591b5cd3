// Draco adapter of the BASE section (codec 2). The only file of formats/
// that includes Draco headers; every Draco exception stops here.
//
// Choices:
// - Sequential connectivity (MESH_SEQUENTIAL_ENCODING): Draco's edgebreaker
//   renumbers vertices, and the progressive mesh's vertex ids (VSPL's vs,
//   vl, vr, the permutation) refer to BASE's order. A base mesh is small,
//   so the few bits edgebreaker would save do not pay for a stored
//   permutation.
// - Positions are quantized by Draco (qp); the normals and texture
//   coordinates of a progressive mesh are float32 elsewhere (VSPL), so they
//   stay unquantized here too. Per-corner attributes are refused: points
//   would have to be split per corner, which changes the vertex ids.
// - The decoder accepts only the bitstream this build writes (version 2.2,
//   triangular mesh, sequential): older bitstream versions have decoders
//   with known unbounded allocations (tests/fuzz/draco_limits).
#include "formats/sections/draco_codec.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "draco/compression/decode.h"
#include "draco/compression/encode.h"
#include "draco/core/decoder_buffer.h"
#include "draco/core/encoder_buffer.h"
#include "draco/mesh/mesh.h"
#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/quantization.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

constexpr size_t kPrefixBytes = 3;  // version, qp, cl

Status bad_draco(const std::string& detail) {
  return malformed_section(kBaseTag, "draco: " + detail);
}

int add_attribute(draco::Mesh* mesh, draco::GeometryAttribute::Type type, int components,
                  const std::vector<float>& values, size_t count) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, static_cast<uint8_t>(components), draco::DT_FLOAT32, false,
                 static_cast<int64_t>(sizeof(float)) * components, 0);
  const int id = mesh->AddAttribute(attribute, true, static_cast<uint32_t>(count));
  draco::PointAttribute* stored = mesh->attribute(id);
  for (size_t i = 0; i < count; ++i) {
    stored->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                              &values[i * components]);
  }
  return id;
}

// Draco 1.5.5 quantizes positions over the float range max - min of the
// widest axis. Past FLT_MAX that range is infinite, the quantized values are
// garbage and its entropy coder then reads through a null pointer (found by
// fuzz_draco_base: a Draco BASE decodes to such a mesh, re-encoding crashed).
// So every coordinate must be finite and every axis's float extent too.
Status check_position_range(const std::vector<Vec3f>& positions) {
  for (const Vec3f& p : positions) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return unsupported("the Draco codec takes finite positions only");
  }
  Vec3f box_min;
  Vec3f box_max;
  bounding_box(positions, &box_min, &box_max);
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box_max[a] - box_min[a])) {
      return unsupported(string_printf(
          "the Draco codec cannot quantize positions spanning %g to %g on axis %d (beyond float)",
          box_min[a], box_max[a], a));
    }
  }
  return Status::ok();
}

Result<Bytes> encode_unchecked(const TriangleMesh& mesh, const DracoOptions& options) {
  for (const MeshAttribute* attr : {&mesh.normals, &mesh.texcoords}) {
    if (attr->present() && attr->binding != AttributeBinding::kPerVertex)
      return unsupported("the Draco codec stores per-vertex attributes only, not per-corner ones");
  }
  if (mesh.triangles.empty()) return unsupported("the Draco codec needs at least one triangle");
  LODBAKE_RETURN_IF_ERROR(check_position_range(mesh.positions));
  const size_t v = mesh.vertex_count();
  draco::Mesh out;
  out.set_num_points(static_cast<uint32_t>(v));
  std::vector<float> flat(3 * v);
  for (size_t i = 0; i < v; ++i)
    std::memcpy(&flat[3 * i], mesh.positions[i].data(), 12);
  add_attribute(&out, draco::GeometryAttribute::POSITION, 3, flat, v);
  if (mesh.normals.present())
    add_attribute(&out, draco::GeometryAttribute::NORMAL, 3, mesh.normals.values, v);
  if (mesh.texcoords.present())
    add_attribute(&out, draco::GeometryAttribute::TEX_COORD, 2, mesh.texcoords.values, v);
  out.SetNumFaces(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k)
      face[k] = draco::PointIndex(mesh.triangles[t][k]);
    out.SetFace(draco::FaceIndex(static_cast<uint32_t>(t)), face);
  }
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  encoder.SetSpeedOptions(10 - options.compression_level, 10 - options.compression_level);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.quantization_bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(out, &buffer);
  if (!status.ok()) return runtime_error("Draco encoding failed: " + status.error_msg_string());
  Bytes bytes = {kDracoBaseVersion, static_cast<uint8_t>(options.quantization_bits),
                 static_cast<uint8_t>(options.compression_level)};
  bytes.insert(bytes.end(), buffer.data(), buffer.data() + buffer.size());
  return bytes;
}

Status check_bitstream_header(const uint8_t* data, size_t size) {
  // "DRACO", major, minor, encoder type (1 = triangular mesh), method (0 = sequential).
  if (size < 9 || std::memcmp(data, "DRACO", 5) != 0) return bad_draco("no Draco header");
  if (data[5] != 2 || data[6] != 2) {
    return bad_draco(
        string_printf("bitstream version %u.%u, this reader takes 2.2", data[5], data[6]));
  }
  if (data[7] != 1 || data[8] != 0)
    return bad_draco("not a triangular mesh with sequential connectivity");
  return Status::ok();
}

Status read_attribute(const draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components,
                      std::vector<float>* out, bool* present) {
  *present = false;
  const int id = mesh.GetNamedAttributeId(type);
  if (id < 0) return Status::ok();
  const draco::PointAttribute* att = mesh.attribute(id);
  // This codec writes float32 only; other types are refused before any
  // read (Draco loads DT_BOOL as a C++ bool, undefined for other bytes).
  if (att->data_type() != draco::DT_FLOAT32)
    return bad_draco(string_printf("attribute of data type %d, not float32",
                                   static_cast<int>(att->data_type())));
  if (att->num_components() != components)
    return bad_draco(string_printf("attribute with %d components", att->num_components()));
  const uint32_t points = mesh.num_points();
  out->resize(size_t{points} * components);
  for (uint32_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex index = att->mapped_index(draco::PointIndex(p));
    if (index.value() >= att->size()) return bad_draco("an attribute does not map every point");
    if (!att->ConvertValue<float>(index, static_cast<int8_t>(components),
                                  &(*out)[size_t{p} * components]))
      return bad_draco("an attribute value cannot be read as float");
  }
  *present = true;
  return Status::ok();
}

Result<TriangleMesh> decode_unchecked(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(DracoOptions options, read_draco_base_options(data, size));
  (void)options;
  LODBAKE_RETURN_IF_ERROR(check_bitstream_header(data + kPrefixBytes, size - kPrefixBytes));
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data + kPrefixBytes), size - kPrefixBytes);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return bad_draco("bitstream refused: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  TriangleMesh out;
  std::vector<float> values;
  bool present = false;
  LODBAKE_RETURN_IF_ERROR(
      read_attribute(*mesh, draco::GeometryAttribute::POSITION, 3, &values, &present));
  if (!present) return bad_draco("no position attribute");
  out.positions.resize(mesh->num_points());
  for (size_t i = 0; i < out.positions.size(); ++i)
    std::memcpy(out.positions[i].data(), &values[3 * i], 12);
  for (auto [type, components, attr] :
       {std::make_tuple(draco::GeometryAttribute::NORMAL, 3, &out.normals),
        std::make_tuple(draco::GeometryAttribute::TEX_COORD, 2, &out.texcoords)}) {
    LODBAKE_RETURN_IF_ERROR(read_attribute(*mesh, type, components, &attr->values, &present));
    if (present) {
      attr->binding = AttributeBinding::kPerVertex;
      attr->components = static_cast<uint32_t>(components);
    }
  }
  out.triangles.resize(mesh->num_faces());
  for (uint32_t f = 0; f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= mesh->num_points()) return bad_draco("a face index is out of range");
      out.triangles[f][k] = face[k].value();
    }
  }
  return out;
}

}  // namespace

Result<Bytes> encode_base_draco(const TriangleMesh& mesh, const DracoOptions& options) {
  if (!is_valid_draco_quantization_bits(options.quantization_bits))
    return invalid_input(string_printf("Draco quantization takes %d to %d bits, not %d",
                                       kMinDracoQuantizationBits, kMaxDracoQuantizationBits,
                                       options.quantization_bits));
  if (options.compression_level < 0 || options.compression_level > 10)
    return invalid_input(
        string_printf("Draco compression level takes 0 to 10, not %d", options.compression_level));
  try {
    return encode_unchecked(mesh, options);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding BASE with Draco");
  } catch (const std::exception& e) {
    return runtime_error(std::string("Draco encoding failed: ") + e.what());
  }
}

Result<DracoOptions> read_draco_base_options(const uint8_t* data, size_t size) {
  if (size < kPrefixBytes) return bad_draco("payload ends inside its first 3 bytes");
  if (data[0] != kDracoBaseVersion) {
    return bad_draco(string_printf("layout version %u is unknown (this reader knows %u)", data[0],
                                   kDracoBaseVersion));
  }
  DracoOptions options;
  options.quantization_bits = data[1];
  options.compression_level = data[2];
  if (options.quantization_bits < kMinDracoQuantizationBits ||
      options.quantization_bits > kMaxStoredDracoQuantizationBits || options.compression_level > 10)
    return bad_draco(string_printf("qp %u or cl %u out of range", data[1], data[2]));
  return options;
}

Result<TriangleMesh> decode_base_draco(const uint8_t* data, size_t size) {
  try {
    return decode_unchecked(data, size);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding a Draco BASE");
  } catch (const std::exception& e) {
    return bad_draco(std::string("bitstream refused: ") + e.what());
  }
}

}  // namespace lodbake
