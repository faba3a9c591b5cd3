// How lodbake-simplify reports the attribute deviation of what it wrote
// (lib/metrics/attribute_deviation.h): JSON for the "metrics" objects and
// the clause of the text report's lines.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/metrics/attribute_deviation.h"

namespace lodbake::cli {

// A level of an asset against the asset: "hausdorff", "hausdorff_relative",
// "mean_relative", "diagonal", the totals "distance", "uv" and
// "normal_degrees" (each {"mean", "p95", "samples"}), and "primitives"
// (per input primitive: "mesh", "primitive", the three stats and
// "max_distance"). An error names --no-metrics.
Result<nlohmann::json> measure_asset_level(const Scene& input, const Scene& level);

// A mesh's UV and normal deviation against its input (both as
// scene_from_mesh() scenes), added to the mesh path's `metrics` object as
// "uv" and "normal_degrees"; the existing fields are left as they are.
Status add_mesh_attribute_metrics(const TriangleMesh& input, const TriangleMesh& output,
                                  nlohmann::json* metrics);

// ", UV mean A p95 B, normal mean C p95 D degrees" from a metrics object
// that has "uv" and "normal_degrees" ("no UV" / "no normal" where the
// input had none to compare); empty otherwise.
std::string attribute_metrics_text(const nlohmann::json& metrics);

// The text report's clause for a level: ", Hausdorff H and mean M of the
// diagonal" and attribute_metrics_text(); empty for a null object.
std::string level_metrics_text(const nlohmann::json& metrics);

// One text line per input primitive of a level's metrics (its "primitives"):
// "  mesh M primitive P  distance max X and mean Y of the diagonal" and
// attribute_metrics_text()'s clause, measured from that primitive's samples
// to the level; empty when there are none.
std::string primitive_metrics_lines(const nlohmann::json& metrics);

}  // namespace lodbake::cli
