#include "tools/common/deviation_report.h"

#include <sstream>

#include "lib/scene/scene_from_mesh.h"

namespace lodbake::cli {
namespace {

nlohmann::json to_json(const DeviationStats& s) {
  return {{"mean", s.mean}, {"p95", s.p95}, {"samples", s.samples}};
}

Status cannot_measure(const Status& status) {
  return Status(status.kind(),
                "cannot measure the attribute deviation from the input (--no-metrics skips it): " +
                    status.message());
}

}  // namespace

Result<nlohmann::json> measure_asset_level(const Scene& input, const Scene& level) {
  Result<SceneDeviation> measured = measure_scene_deviation(input, level);
  if (!measured.is_ok()) return cannot_measure(measured.status());
  const SceneDeviation& d = measured.value();
  nlohmann::json primitives = nlohmann::json::array();
  for (const PrimitiveDeviation& p : d.primitives)
    primitives.push_back({{"mesh", p.mesh},
                          {"primitive", p.primitive},
                          {"distance", to_json(p.distance)},
                          {"max_distance", p.max_distance},
                          {"uv", to_json(p.uv)},
                          {"normal_degrees", to_json(p.normal_degrees)}});
  return nlohmann::json{{"hausdorff_relative", d.hausdorff_relative},
                        {"mean_relative", d.mean_relative},
                        {"hausdorff", d.hausdorff},
                        {"diagonal", d.diagonal},
                        {"distance", to_json(d.distance)},
                        {"uv", to_json(d.uv)},
                        {"normal_degrees", to_json(d.normal_degrees)},
                        {"primitives", std::move(primitives)}};
}

Status add_mesh_attribute_metrics(const TriangleMesh& input, const TriangleMesh& output,
                                  nlohmann::json* metrics) {
  if (!input.normals.present() && !input.texcoords.present()) {
    // Nothing to compare: what the measurement would say, without its cost.
    (*metrics)["uv"] = (*metrics)["normal_degrees"] = to_json(DeviationStats{});
    return Status::ok();
  }
  Result<Scene> a = scene_from_mesh(input, "input");
  if (!a.is_ok()) return cannot_measure(a.status());
  Result<Scene> b = scene_from_mesh(output, "output");
  if (!b.is_ok()) return cannot_measure(b.status());
  Result<SceneDeviation> measured = measure_scene_deviation(a.value(), b.value());
  if (!measured.is_ok()) return cannot_measure(measured.status());
  (*metrics)["uv"] = to_json(measured.value().uv);
  (*metrics)["normal_degrees"] = to_json(measured.value().normal_degrees);
  return Status::ok();
}

std::string attribute_metrics_text(const nlohmann::json& metrics) {
  if (!metrics.is_object() || !metrics.contains("uv") || !metrics.contains("normal_degrees"))
    return "";
  std::ostringstream text;
  auto stats = [&](const char* label, const nlohmann::json& s, const char* unit) {
    if (s["samples"].get<uint64_t>() == 0) {
      text << ", no " << label;
    } else {
      text << ", " << label << " mean " << s["mean"].get<double>() << " p95 "
           << s["p95"].get<double>() << unit;
    }
  };
  stats("UV", metrics["uv"], "");
  stats("normal", metrics["normal_degrees"], " degrees");
  return text.str();
}

std::string level_metrics_text(const nlohmann::json& metrics) {
  if (metrics.is_null()) return "";
  std::ostringstream text;
  text << ", Hausdorff " << metrics["hausdorff_relative"].get<double>() << " and mean "
       << metrics["mean_relative"].get<double>() << " of the diagonal";
  return text.str() + attribute_metrics_text(metrics);
}

std::string primitive_metrics_lines(const nlohmann::json& metrics) {
  if (!metrics.is_object() || !metrics.contains("primitives")) return "";
  const double diagonal = metrics["diagonal"].get<double>();
  std::ostringstream text;
  for (const nlohmann::json& p : metrics["primitives"]) {
    text << "  mesh " << p["mesh"].get<uint64_t>() << " primitive "
         << p["primitive"].get<uint64_t>();
    if (p["distance"]["samples"].get<uint64_t>() == 0 || !(diagonal > 0)) {
      text << "  no samples";
    } else {
      text << "  distance max " << p["max_distance"].get<double>() / diagonal << " and mean "
           << p["distance"]["mean"].get<double>() / diagonal << " of the diagonal";
    }
    text << attribute_metrics_text(p) << "\n";
  }
  return text.str();
}

}  // namespace lodbake::cli
