// Repacking lodbake containers: merge the sections of several containers
// baked from the same input, drop or keep sections, and recode the section
// kinds lodbake-pack knows (BASE, VSPL, VTRE, ...) compactly or with Draco. What
// `lodbake-pack A.lbk [B.lbk ...] -o OUT.lbk` runs; memory in, memory out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/sections/draco_codec.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

struct PackInput {
  std::string name;  ///< for messages and the report (e.g. the file's name)
  Bytes bytes;       ///< the whole container
};

struct RepackOptions {
  /// Quantize float32 (or differently quantized) BASE and VSPL positions to
  /// this many bits (1..30); 0 keeps the positions' encoding.
  int quantize_bits = 0;
  /// Round VSPL collapse errors up to this many significant bits (1..24,
  /// round_vspl_errors()); 0 keeps them as they are.
  int error_bits = 0;
  /// Store VSPL and the kinds of formats/sections/compact_sections.h with
  /// the compact codec (else raw).
  bool compact = true;
  /// Store BASE with the Draco codec (`draco` options); a float32 VSPL is
  /// then quantized to draco.quantization_bits unless quantize_bits is set.
  bool draco = false;
  DracoOptions draco_options;
  /// When not empty, only these tags are written (META is always written
  /// unless dropped).
  std::vector<std::string> keep;
  /// Tags not written.
  std::vector<std::string> drop;
  /// The threads a group's sections after BASE are coded on (ParallelScope:
  /// 0 is the caller's arena, every core or a bake's --jobs); the output is
  /// the same bytes for any count.
  unsigned threads = 0;
};

/// What happened to one section of the output (or a dropped one).
struct PackedSection {
  std::string tag;
  uint32_t group = 0;          ///< its group in the output (docs/format.md "Groups")
  std::string source;          ///< the input it came from
  std::string codec_before;    ///< "raw", "compact", "draco" or the number
  std::string codec_after;     ///< empty when dropped
  uint64_t stored_before = 0;  ///< bytes in the source file
  uint64_t stored_after = 0;   ///< bytes in the output (0 when dropped)
  uint64_t decoded_after = 0;  ///< its raw payload's size
  std::string action;          ///< "recoded", "copied", "rewritten" (META) or "dropped"
};

struct PackResult {
  Bytes file;                           ///< the output container
  std::vector<PackedSection> sections;  ///< output order, then the dropped ones
  uint64_t input_bytes = 0;             ///< all inputs together
  uint64_t vertices = 0;   ///< of the fully refined mesh (BASE + VSPL), else BASE's; 0 without
  uint64_t triangles = 0;  ///< likewise
  uint64_t splits = 0;     ///< VSPL's records, 0 without
};

/// Merges, filters and recodes `inputs` into one container. Deterministic:
/// the output is a function of the inputs' sections and the options, with
/// META first, then BASE, VSPL, then the other sections in the order they
/// first appear. Sections of the kinds with a compact codec
/// (formats/sections/compact_sections.h) are written compact (or raw),
/// their raw payloads unchanged; sections of a kind this function does not
/// recode are copied byte for byte (codec and sizes included). A BASE
/// already stored as requested is copied, so packing a packed file with the
/// same options gives the same bytes. The output META records
/// lodbake-pack, `options`, the common input, the union of the inputs'
/// counts, and the inputs' provenance ("sources": tool, version and options
/// of each, flattened through earlier packs).
/// \return kInvalidInput when an input is not a valid container or holds a
///         malformed section of a kind it recodes, inputs disagree on the
///         input hash, a tag occurs in two inputs with different contents,
///         counts disagree, or VSPL would be written without BASE;
///         kUnsupported for a codec this build lacks.
/// `meta_options` is what the output META records as the options (the
/// tool's own spelling). When the failure concerns one input, its index is
/// stored in `*failed_input` (else inputs.size()), so a tool can name it.
/// `inputs` is taken by value: a caller done with its inputs moves them in,
/// and the containers are read in place instead of copied.
Result<PackResult> repack_containers(std::vector<PackInput> inputs, const RepackOptions& options,
                                     const nlohmann::json& meta_options, size_t* failed_input);

}  // namespace lodbake
