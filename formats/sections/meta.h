// The META section: provenance of a container as one UTF-8 JSON object
// (which tool wrote it, lodbake version, options, input file, counts).
// Byte layout and the key list: docs/format.md "META".
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// Largest META payload a reader accepts (and a writer produces).
inline constexpr size_t kMaxMetaBytes = size_t{1} << 20;
/// Deepest nesting of arrays/objects accepted anywhere in the document.
inline constexpr int kMaxMetaDepth = 64;

/// The input file a container was baked from.
struct MetaInput {
  std::string file_name;   ///< as the user gave it (no directory policy imposed)
  std::string sha256_hex;  ///< SHA-256 of the file's bytes: 64 lower-case hex digits
  uint64_t bytes = 0;      ///< the file's size

  bool operator==(const MetaInput& o) const {
    return file_name == o.file_name && sha256_hex == o.sha256_hex && bytes == o.bytes;
  }
};

/// The decoded META object. JSON keys: "tool", "version", "options",
/// "input" {"file", "sha256", "bytes"}, "counts"; any other top-level key is
/// kept in `extra` so that a newer writer's additions survive a round trip.
struct MetaSection {
  std::string tool;                                   ///< e.g. "lodbake-simplify"
  std::string version;                                ///< lodbake version that wrote it
  nlohmann::json options = nlohmann::json::object();  ///< the tool's options, a JSON object
  std::optional<MetaInput> input;                     ///< absent for files not baked from one input
  std::map<std::string, uint64_t> counts;             ///< e.g. {"vertices": 8, "triangles": 12}
  nlohmann::json extra = nlohmann::json::object();    ///< other top-level keys

  bool operator==(const MetaSection& o) const {
    return tool == o.tool && version == o.version && options == o.options && input == o.input &&
           counts == o.counts && extra == o.extra;
  }
};

/// A META for `tool` with version = kLodbakeVersion and everything else empty.
MetaSection make_meta(std::string tool);

/// The JSON object for `meta`: "tool", "version", "options" and "counts"
/// always (possibly {}), "input" only when present, plus the `extra` keys.
/// \pre `meta` passes encode_meta()'s checks (otherwise the object may not
///      decode again).
nlohmann::json meta_to_json(const MetaSection& meta);

/// The META payload: meta_to_json(meta) dumped compactly (no whitespace,
/// keys sorted by byte value, UTF-8 unescaped), so equal inputs give equal
/// bytes. Fails with kInvalidInput when tool or version is empty, options is
/// not an object, sha256_hex is not 64 lower-case hex digits, `extra` is not
/// an object or repeats a standard key, a string is not valid UTF-8, a number
/// is not finite, nesting exceeds kMaxMetaDepth, or the result would exceed
/// kMaxMetaBytes.
Result<Bytes> encode_meta(const MetaSection& meta);

/// Parses a META payload. Fails with LBK-E023 ("section META: ...",
/// kInvalidInput) when it exceeds kMaxMetaBytes, nests deeper than
/// kMaxMetaDepth, is not valid UTF-8 JSON, is not an object, lacks the
/// string keys "tool" and "version", or a standard key has the wrong type
/// (options not an object, input not {file: string, sha256: 64 lower-case
/// hex, bytes: unsigned}, counts not an object of unsigned integers).
/// Never throws; the nesting limit is checked on the raw bytes before parsing.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
Result<MetaSection> decode_meta(const uint8_t* data, size_t size);

/// The parsed document itself, with the same checks as decode_meta(), for
/// printing it whole (inspect --json).
Result<nlohmann::json> decode_meta_json(const uint8_t* data, size_t size);

}  // namespace lodbake
