// The WEDG section: the wedges of the progressive mesh in its group's BASE
// and VSPL (formats/mesh/pm_wedges.h), so that every level of an asset's
// mesh is a textured mesh; in a group without VSPL (a fan hierarchy's), the
// wedges of BASE's own corners, with no splits. The attribute values are the asset's (SCNE);
// WEDG says which vertex of which primitive each corner uses. Byte layout:
// docs/format.md "WEDG".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// Header bytes: flags, then the wedge, base triangle, split and moved
/// corner counts (u32 each).
inline constexpr size_t kWedgFixedBytes = 20;

/// Encodes `wedges`. \return kInvalidInput ("cannot encode WEDG: ...") when
/// its lists do not fit together (PmWedges' invariants).
Result<Bytes> encode_wedg(const PmWedges& wedges);

/// Decodes a WEDG payload. \return LBK-E023 "section WEDG: ..." when the
/// size is not exactly what the counts give, flags are unknown, a wedge
/// index is out of range, the moved counts do not add up, or an added face
/// has some wedges and not others. Counts are bounded by the payload's size
/// before anything is allocated.
Result<PmWedges> decode_wedg(const uint8_t* data, size_t size);

/// What WEDG must agree on with its group's progressive mesh: as many base
/// triangles and splits, and a split's added faces where it has wings.
/// Empty when they agree. (Whether each split moves as many faces as WEDG
/// says is known only by replaying it: lib/simplify/wedge_replay.h.)
std::vector<std::string> validate_wedg(const PmWedges& wedges, const ProgressiveMesh& pm);

/// What WEDG must be in a group without VSPL (a fan hierarchy's, whose
/// fronts take their wedges from the input's corners): the corners of
/// BASE's triangles, so no splits, one corner triple per triangle, each
/// corner's wedge homed at the corner's own vertex, a face's three wedges of
/// one primitive. Empty when it is; else the first problem.
std::vector<std::string> validate_wedg_corners(const PmWedges& wedges, const TriangleMesh& base);

}  // namespace lodbake
