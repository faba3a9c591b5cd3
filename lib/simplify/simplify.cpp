// simplify(): validates the input and options, runs the collapse engine
// (collapse_engine.cpp) and assembles the simplified mesh and, when asked,
// the progressive mesh (pm_record.cpp). Stop criteria: the smallest of
// target_triangles and floor(target_ratio * input triangles), and max_error
// compared with sqrt(collapse cost) / bounding-box diagonal.
#include "lib/simplify/simplify.h"

#include <cmath>
#include <limits>
#include <new>
#include <string>

#include "lib/simplify/collapse_engine.h"
#include "lib/simplify/mesh_topology.h"
#include "lib/simplify/pm_record.h"
#include "lib/simplify/vertex_order.h"

namespace lodbake {
namespace {

using simplify_internal::EngineSettings;
using simplify_internal::EngineState;

// Below this many input triangles the output mesh and the progressive mesh
// are assembled one after the other: starting a thread would cost more.
constexpr uint64_t kParallelAssembly = 8192;

Status check_attribute(const MeshAttribute& attr, const char* name, uint32_t components,
                       const TriangleMesh& mesh) {
  if (!attr.present()) return Status::ok();
  if (attr.components != components || attr.values.size() % components != 0) {
    return invalid_input(std::string(name) + " have " + std::to_string(attr.components) +
                         " components, expected " + std::to_string(components));
  }
  if (attr.binding == AttributeBinding::kPerVertex) {
    if (attr.value_count() != mesh.positions.size()) {
      return invalid_input(std::string(name) + ": " + std::to_string(attr.value_count()) +
                           " per-vertex values for " + std::to_string(mesh.positions.size()) +
                           " vertices");
    }
    return Status::ok();
  }
  if (attr.corners.size() != mesh.triangles.size()) {
    return invalid_input(std::string(name) + ": " + std::to_string(attr.corners.size()) +
                         " corner triples for " + std::to_string(mesh.triangles.size()) +
                         " triangles");
  }
  for (size_t t = 0; t < attr.corners.size(); ++t) {
    for (uint32_t i : attr.corners[t]) {
      if (i >= attr.value_count()) {
        return invalid_input(std::string(name) + ": triangle " + std::to_string(t) +
                             " uses value " + std::to_string(i) + " out of range (" +
                             std::to_string(attr.value_count()) + " values)");
      }
    }
  }
  return Status::ok();
}

Status check_options(const SimplifyOptions& o) {
  if (o.target_ratio && !(*o.target_ratio > 0 && *o.target_ratio <= 1)) {
    return Status(ErrorKind::kUsage, "target ratio must be in (0, 1]");
  }
  if (o.max_error && !(*o.max_error >= 0)) {
    return Status(ErrorKind::kUsage, "maximum error must not be negative");
  }
  if (!(o.boundary_weight >= 0) || !std::isfinite(o.boundary_weight)) {
    return Status(ErrorKind::kUsage, "boundary weight must be a finite non-negative number");
  }
  if (!(o.max_normal_change_degrees >= 0 && o.max_normal_change_degrees <= 180)) {
    return Status(ErrorKind::kUsage, "maximum normal change must be in [0, 180] degrees");
  }
  if (o.height_guard && o.placement != Placement::kHalf) {
    return Status(ErrorKind::kUsage, "the height guard needs half placement");
  }
  if (o.height_guard && !is_valid_height_guard_factor(o.height_guard_factor)) {
    return Status(ErrorKind::kUsage, "the height guard's factor must be a finite number above 0");
  }
  return Status::ok();
}

// Of the referenced vertices (those with faces in `topology`), read in
// vertex order rather than through the triangles.
double bbox_diagonal(const TriangleMesh& mesh, const simplify_internal::MeshTopology& topology) {
  if (mesh.triangles.empty()) return 0;
  Vec3f lo = mesh.positions[mesh.triangles[0][0]];
  Vec3f hi = lo;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (topology.face_start[v] == topology.face_start[v + 1]) continue;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], mesh.positions[v][k]);
      hi[k] = std::max(hi[k], mesh.positions[v][k]);
    }
  }
  double d = 0;
  for (int k = 0; k < 3; ++k)
    d += (double{hi[k]} - lo[k]) * (double{hi[k]} - lo[k]);
  return std::sqrt(d);
}

// The simplified mesh: live triangles in input order, referenced vertices in
// input order.
TriangleMesh assemble_mesh(const EngineState& state, std::vector<uint32_t>* sources) {
  TriangleMesh out;
  std::vector<uint32_t> remap(state.positions.size(), kNoVertex);
  for (size_t t = 0; t < state.triangles.size(); ++t) {
    if (!state.triangle_alive[t]) continue;
    for (uint32_t v : state.triangles[t])
      remap[v] = 0;
  }
  std::vector<uint32_t> order;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == kNoVertex) continue;
    remap[v] = static_cast<uint32_t>(order.size());
    order.push_back(static_cast<uint32_t>(v));
    out.positions.push_back(state.positions[v]);
  }
  for (size_t t = 0; t < state.triangles.size(); ++t) {
    if (!state.triangle_alive[t]) continue;
    const Triangle& tri = state.triangles[t];
    out.triangles.push_back({remap[tri[0]], remap[tri[1]], remap[tri[2]]});
  }
  const MeshAttribute* in_attrs[2] = {&state.normals, &state.texcoords};
  MeshAttribute* out_attrs[2] = {&out.normals, &out.texcoords};
  for (int a = 0; a < 2; ++a) {
    const MeshAttribute& in = *in_attrs[a];
    MeshAttribute& o = *out_attrs[a];
    if (!in.present()) continue;
    o.binding = in.binding;
    o.components = in.components;
    if (in.binding == AttributeBinding::kPerVertex) {
      for (uint32_t v : order) {
        const float* src = &in.values[size_t{v} * in.components];
        o.values.insert(o.values.end(), src, src + in.components);
      }
    } else {
      // Values are kept whole (several vertices may share one); only the
      // corner triples of the live triangles remain.
      o.values = in.values;
      for (size_t t = 0; t < state.triangles.size(); ++t) {
        if (state.triangle_alive[t]) o.corners.push_back(in.corners[t]);
      }
    }
  }
  *sources = std::move(order);
  return out;
}

// `owned`, when given, is `input` itself, handed over by the caller: its
// positions and triangles are freed once the engine's renumbered copy is
// checked, so that the engine's is the only copy of the mesh at the peak.
Result<SimplifyResult> simplify_impl(const TriangleMesh& input, TriangleMesh* owned,
                                     const SimplifyOptions& options) {
  LODBAKE_RETURN_IF_ERROR(check_options(options));
  // The engine names a half-edge 3 * triangle + corner in 32 bits.
  if (input.triangles.size() > kMaxSimplifyTriangles)
    return unsupported(std::to_string(input.triangles.size()) +
                       " triangles, more than the in-core simplifier takes (" +
                       std::to_string(kMaxSimplifyTriangles) + "); use --memory-limit");
  if (!options.locked_vertices.empty() && options.locked_vertices.size() != input.positions.size())
    return invalid_input("locked_vertices has " + std::to_string(options.locked_vertices.size()) +
                         " flags for " + std::to_string(input.positions.size()) + " vertices");
  LODBAKE_RETURN_IF_ERROR(check_attribute(input.normals, "normals", 3, input));
  LODBAKE_RETURN_IF_ERROR(check_attribute(input.texcoords, "texture coordinates", 2, input));
  if (options.record_pm && (input.normals.binding == AttributeBinding::kPerCorner ||
                            input.texcoords.binding == AttributeBinding::kPerCorner)) {
    return unsupported(
        "a progressive mesh cannot record per-corner attributes; make them per-vertex first "
        "(split the vertices on seams)");
  }
  // The engine runs on the vertices renumbered for locality
  // (vertex_order.h); the state is turned back to input ids afterwards.
  std::vector<uint32_t> order;
  const bool renumber = simplify_internal::locality_order(input, &order);
  TriangleMesh renumbered =
      renumber ? simplify_internal::renumbered_mesh(input, order) : TriangleMesh();
  const TriangleMesh& work = renumber ? renumbered : input;
  // The engine reads the faces of the corner lists only for per-corner
  // attributes (seams).
  const bool per_corner = input.normals.binding == AttributeBinding::kPerCorner ||
                          input.texcoords.binding == AttributeBinding::kPerCorner;
  const ParallelScope threads(options.threads);
  simplify_internal::MeshTopology topology;
  const Status valid = simplify_internal::build_topology(work, &topology, per_corner, &threads);
  if (!valid.is_ok()) {
    // Name the problem in input ids, and the first one in input order.
    simplify_internal::MeshTopology unused;
    LODBAKE_RETURN_IF_ERROR(simplify_internal::build_topology(input, &unused));
    return valid;
  }
  // Only the attributes are read from the input past this point
  // (record_progressive_mesh()), and the triangle count, kept here.
  const uint64_t input_triangles = input.triangles.size();
  if (owned && renumber) {
    owned->positions = std::vector<Vec3f>();
    owned->triangles = std::vector<Triangle>();
  }

  EngineSettings settings;
  settings.diagonal = bbox_diagonal(work, topology);
  if (renumber) settings.input_ids = &order;
  settings.threads = &threads;
  settings.target_triangles = 0;
  if (options.target_triangles) settings.target_triangles = *options.target_triangles;
  if (options.target_ratio) {
    const auto by_ratio = static_cast<uint64_t>(
        std::floor(*options.target_ratio * static_cast<double>(input_triangles)));
    if (!options.target_triangles || by_ratio > settings.target_triangles) {
      // Both given: stop at the first reached, i.e. the larger count.
      settings.target_triangles = by_ratio;
    }
  }
  settings.max_cost = std::numeric_limits<double>::infinity();
  if (options.max_error) {
    const double d = *options.max_error * settings.diagonal;
    settings.max_cost = d * d;
  }

  // The renumbered copy is not needed afterwards: the engine takes its arrays.
  EngineState state = simplify_internal::run_collapse_engine(
      renumber ? std::move(renumbered) : input, std::move(topology), options, settings);
  if (renumber) simplify_internal::restore_input_ids(order, &state);
  SimplifyResult result;
  result.stats = state.stats;
  // Both only read the state.
  auto assemble = [&](size_t task) {
    if (task == 0) {
      result.mesh = assemble_mesh(state, &result.vertex_sources);
    } else if (options.record_pm) {
      result.pm = simplify_internal::record_progressive_mesh(input, state);
    }
  };
  if (options.record_pm && input_triangles >= kParallelAssembly) {
    threads.for_each_part(2, assemble);
  } else {
    assemble(0);
    assemble(1);
  }
  return result;
}

}  // namespace

Result<SimplifyResult> simplify(const TriangleMesh& input, const SimplifyOptions& options) {
  try {
    return simplify_impl(input, nullptr, options);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while simplifying " +
                         std::to_string(input.triangles.size()) + " triangles");
  }
}

Result<SimplifyResult> simplify(TriangleMesh&& input, const SimplifyOptions& options) {
  const size_t triangles = input.triangles.size();
  try {
    return simplify_impl(input, &input, options);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while simplifying " + std::to_string(triangles) +
                         " triangles");
  }
}

}  // namespace lodbake
