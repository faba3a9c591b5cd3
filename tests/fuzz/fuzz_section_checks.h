// Checks shared by the container and BASE fuzz targets: decode a section
// payload, validate it, and assert the round-trip invariants of the format.
// A failed invariant aborts, which the fuzzer (or the corpus replay under
// the sanitizers) reports as a crash.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "formats/sections/base.h"
#include "formats/sections/meta.h"

namespace lodbake::fuzz {

inline void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz invariant failed: %s\n", what);
    std::abort();
  }
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
    require(mesh.status().code() == 23 || mesh.status().kind() == ErrorKind::kRuntime,
            "BASE decode error without LBK-E023");
    return;
  }
  require(summary.is_ok(), "BASE decodes but its summary does not");
  require(summary.value().vertex_count == mesh.value().positions.size(), "summary vertex count");
  (void)validate_base(mesh.value());
  Result<Bytes> again = encode_base(mesh.value(), {});
  require(again.is_ok(), "decoded BASE mesh cannot be encoded");
  if (decoded_summary.position_encoding == PositionEncoding::kFloat32) {
    require(again.value().size() == size &&
                (size == 0 || std::memcmp(again.value().data(), data, size) == 0),
            "float32 BASE is not canonical");
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
    require(meta.status().code() == 23 || meta.status().kind() == ErrorKind::kRuntime,
            "META decode error without LBK-E023");
    return;
  }
  Result<Bytes> again = encode_meta(meta.value());
  if (!again.is_ok()) return;  // e.g. an empty tool name, or growth past 1 MiB
  Result<MetaSection> back = decode_meta(again.value().data(), again.value().size());
  require(back.is_ok() && back.value() == meta.value(), "META round trip");
}

}  // namespace lodbake::fuzz
