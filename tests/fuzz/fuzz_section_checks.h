// Checks shared by the section fuzz targets: decode a section payload,
// validate it, and assert the round-trip invariants of the format.
// A failed invariant aborts, which the fuzzer (or the corpus replay under
// the sanitizers) reports as a crash.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/vspl.h"

namespace lodbake::fuzz {

inline void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz invariant failed: %s\n", what);
    std::abort();
  }
}

// A decoder may refuse a payload only as malformed input (LBK-E023) or, for
// an allocation it cannot make, as a runtime error.
inline void require_decode_error(const Status& status, const char* what) {
  require(status.code() == 23 || status.kind() == ErrorKind::kRuntime, what);
}

// A canonical format re-encodes what it decoded to the input, byte for byte.
inline void require_same_bytes(const Bytes& again, const uint8_t* data, size_t size,
                               const char* what) {
  require(again.size() == size && (size == 0 || std::memcmp(again.data(), data, size) == 0), what);
}

// BASE: float32 payloads are canonical, so re-encoding what decoded must
// give the input back byte for byte; quantized ones must at least re-decode
// to the same mesh when stored as float32.
inline void check_base_payload(const uint8_t* data, size_t size) {
  Result<BaseSummary> summary = read_base_summary(data, size);
  BaseSummary decoded_summary;
  Result<TriangleMesh> mesh = decode_base(data, size, &decoded_summary);
  (void)validate_base_payload(data, size);
  if (!mesh.is_ok()) {
    require_decode_error(mesh.status(), "BASE decode error without LBK-E023");
    return;
  }
  require(summary.is_ok(), "BASE decodes but its summary does not");
  require(summary.value().vertex_count == mesh.value().positions.size(), "summary vertex count");
  (void)validate_base(mesh.value());
  Result<Bytes> again = encode_base(mesh.value(), {});
  require(again.is_ok(), "decoded BASE mesh cannot be encoded");
  if (decoded_summary.position_encoding == PositionEncoding::kFloat32) {
    require_same_bytes(again.value(), data, size, "float32 BASE is not canonical");
  }
  Result<TriangleMesh> back = decode_base(again.value().data(), again.value().size());
  require(back.is_ok() && back.value() == mesh.value(), "BASE float32 round trip");
}

// META: what decodes re-encodes (unless too large) to the same document.
inline void check_meta_payload(const uint8_t* data, size_t size) {
  Result<MetaSection> meta = decode_meta(data, size);
  Result<nlohmann::json> doc = decode_meta_json(data, size);
  require(meta.is_ok() == doc.is_ok(), "decode_meta and decode_meta_json disagree");
  if (!meta.is_ok()) {
    require_decode_error(meta.status(), "META decode error without LBK-E023");
    return;
  }
  Result<Bytes> again = encode_meta(meta.value());
  if (!again.is_ok()) return;  // e.g. an empty tool name, or growth past 1 MiB
  Result<MetaSection> back = decode_meta(again.value().data(), again.value().size());
  require(back.is_ok() && back.value() == meta.value(), "META round trip");
}

// Largest synthetic base mesh the VSPL check builds for a bare payload, so a
// hostile base vertex count cannot make the harness itself allocate much.
inline constexpr uint32_t kMaxSyntheticBaseVertices = 4096;

// A stand-in base mesh for a bare VSPL payload: `vertices` positions and,
// when the flags say the PM carries them, per-vertex normals and texture
// coordinates, so that join_progressive_mesh() accepts it.
inline TriangleMesh synthetic_base(uint32_t vertices, uint8_t flags) {
  TriangleMesh base;
  for (uint32_t i = 0; i < vertices; ++i)
    base.positions.push_back({static_cast<float>(i), 0.5f * static_cast<float>(i), -1.0f});
  if ((flags & kVsplStoresNormals) != 0) {
    base.normals.binding = AttributeBinding::kPerVertex;
    base.normals.components = 3;
    for (uint32_t i = 0; i < vertices; ++i)
      base.normals.values.insert(base.normals.values.end(), {0.0f, -0.0f, 1.0f});
  }
  if ((flags & kVsplStoresTexcoords) != 0) {
    base.texcoords.binding = AttributeBinding::kPerVertex;
    base.texcoords.components = 2;
    for (uint32_t i = 0; i < vertices; ++i)
      base.texcoords.values.insert(base.texcoords.values.end(), {static_cast<float>(i), 0.25f});
  }
  return base;
}

// VSPL: decoded against `base` (the container's BASE) or, when null,
// against a synthetic base of the stored base vertex count with the
// attributes the flags announce. What decodes and joins its base passes
// validation and re-encodes (float32) to the same progressive mesh, and to
// the same bytes when the input was float32 with the flags the writer would
// choose.
inline void check_vspl_payload(const uint8_t* data, size_t size, const TriangleMesh* base) {
  Result<VsplSummary> summary = read_vspl_summary(data, size);
  TriangleMesh synthetic;
  if (base == nullptr) {
    if (summary.is_ok() && summary.value().base_vertex_count <= kMaxSyntheticBaseVertices) {
      synthetic = synthetic_base(summary.value().base_vertex_count, summary.value().flags);
    }
    base = &synthetic;
  }
  VsplSummary decoded_summary;
  Result<VsplSection> section = decode_vspl(data, size, base->positions, &decoded_summary);
  (void)validate_vspl_payload(data, size, base->positions);
  if (!section.is_ok()) {
    require_decode_error(section.status(), "VSPL decode error without LBK-E023");
    return;
  }
  require(summary.is_ok(), "VSPL decodes but its summary does not");
  require(summary.value().split_count == section.value().splits.size() &&
              summary.value().full_vertex_count() == section.value().input_vertex.size() &&
              decoded_summary.flags == summary.value().flags,
          "VSPL summary disagrees with the decoded records");
  Result<ProgressiveMesh> joined = join_progressive_mesh(*base, section.value());
  if (!joined.is_ok()) {
    // Only a container's BASE can disagree with the VSPL's attributes.
    require(joined.status().code() == 23 && base != &synthetic, "VSPL does not join its base");
    return;
  }
  const ProgressiveMesh& pm = joined.value();
  require(validate_vspl(pm).empty(), "decoded VSPL fails validation");
  Result<Bytes> again = encode_vspl(pm, {});
  require(again.is_ok(), "decoded VSPL cannot be encoded");
  Result<VsplSection> back =
      decode_vspl(again.value().data(), again.value().size(), base->positions);
  require(back.is_ok(), "re-encoded VSPL does not decode");
  Result<ProgressiveMesh> rejoined = join_progressive_mesh(*base, back.value());
  require(rejoined.is_ok() && rejoined.value() == pm, "VSPL float32 round trip");
  if (decoded_summary.position_encoding == PositionEncoding::kFloat32 &&
      back.value().summary.flags == decoded_summary.flags) {
    require_same_bytes(again.value(), data, size, "float32 VSPL is not canonical");
  }
}

}  // namespace lodbake::fuzz
