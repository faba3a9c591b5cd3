// The compact codec (codec 1) of the VSPL section: a lossless recoding of a
// raw VSPL payload (docs/format.md "Compact VSPL"). Layout version 4 is
// version 3 with the errors' common zero low bits left out (errors rounded
// by round_vspl_errors()), written when there are any. Layout version 3: the
// connectivity replayed split by split, vs by its degree class and rank,
// wings coded by their place in vs's current fan, quantized positions
// predicted from vt's fan by stored weights, errors as predicted
// differences and the permutation as ranks among the unused ids, all
// through an adaptive range coder. Version 2 (still read, and written on
// request): vs by its 64th of the ids, vt from the fan's centroid, the
// permutation as id differences. Version 1 (still read, and written when
// smaller, on tiny PMs, or on request): wings from lists of known
// neighbours, Exp-Golomb codes, permutation verbatim. Decoding gives back
// the raw payload byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

struct VsplSection;

/// The newest layout version; readers accept 1 to 4.
inline constexpr uint8_t kVsplCompactVersion = 4;

/// What each part of a version-2, -3 or -4 payload costs, in bits: the range coder's
/// information content of the part's decisions (the stream's 5 framing
/// bytes excluded), and the bytes copied verbatim.
struct VsplCompactStats {
  double vs_bits = 0;
  double wing_bits = 0;
  double position_bits = 0;
  double error_bits = 0;
  double permutation_bits = 0;
  uint64_t verbatim_bytes = 0;  ///< float32 positions, normals, texture coordinates
};

struct VsplCompactOptions {
  /// 1 to 4; 0 (the default): the newest that pays, N = 4 when the errors
  /// have common zero low bits (rounded with round_vspl_errors()), else
  /// N = 3; below 4096 splits, writes versions 1 and N and keeps the
  /// smaller, N on a tie (its adaptive models need a few hundred splits to
  /// learn, so version 1 stays smaller on tiny progressive meshes); from
  /// 4096 splits on, version N.
  uint8_t version = 0;
  /// Filled in with the range-coded encoding's costs when not null.
  VsplCompactStats* stats = nullptr;
  /// When not null: the payload as decode_vspl(raw, raw_size,
  /// base.positions) gives it, which the caller has already decoded (the
  /// encoder would decode it again).
  const VsplSection* decoded = nullptr;
};

/// Recodes a raw VSPL payload. `base` is the decoded BASE mesh the payload
/// belongs to (its positions predict the first splits, its triangles are
/// the connectivity the splits refine). Deterministic.
/// \return the compact bytes; decode_vspl()'s error when the raw payload is
///         malformed; kInvalidInput for an unknown version or a base
///         triangle out of range; kRuntime when memory runs out.
Result<Bytes> encode_vspl_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base,
                                  const VsplCompactOptions& options = {});

/// The raw VSPL payload that `data` encodes, against the same `base`.
/// Every count is bounded by the bytes that remain before anything is
/// allocated. The result is not validated as a VSPL payload: decode it with
/// decode_vspl() as any raw payload.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section VSPL: compact ..." (kInvalidInput) for an
///         unknown version, a base vertex count other than base's, a count
///         needing more bits than remain, an index, residual or code out of
///         range, a record with both wings missing or a repeated vertex,
///         nonzero padding bits (version 1), a range-coded stream that is
///         not canonical (versions 2 to 4), an error shift over 31 or not the
///         errors' largest (version 4) or trailing bytes; kRuntime when
///         memory runs out. Never throws.
Result<Bytes> decode_vspl_compact(const uint8_t* data, size_t size, const TriangleMesh& base);

}  // namespace lodbake
