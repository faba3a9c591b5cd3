#include "lib/scene/scene_lods.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "formats/scene/accessor_values.h"
#include "lib/scene/scene_topology.h"
#include "lib/simplify/pm_wedge_assignment.h"
#include "lib/simplify/wedge_pm.h"

namespace lodbake {
namespace {

using PositionKey = std::array<uint32_t, 3>;

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t v : k)
      h = (h ^ v) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

PositionKey key_of(const Vec3f& p) {
  PositionKey k;
  std::memcpy(k.data(), p.data(), sizeof(k));
  return k;
}

// A triangle by its corners' positions, rotated to start at the smallest,
// so that the same oriented triangle gives the same key from any corner.
using TriangleKey = std::array<PositionKey, 3>;

struct TriangleKeyHash {
  size_t operator()(const TriangleKey& k) const {
    PositionKeyHash h;
    return h(k[0]) * 31 + h(k[1]) * 7 + h(k[2]);
  }
};

// The key and the rotation r such that key[i] is corner (i + r) % 3.
TriangleKey rotated_key(const PositionKey& a, const PositionKey& b, const PositionKey& c, int* r) {
  const PositionKey corners[3] = {a, b, c};
  int first = 0;
  for (int i = 1; i < 3; ++i)
    if (corners[i] < corners[first]) first = i;
  *r = first;
  return {corners[first], corners[(first + 1) % 3], corners[(first + 2) % 3]};
}

// For one triangle of the mesh the engine takes (the welded topology,
// repaired): the input triangle it is and, for each of its corners, which
// corner of that input triangle.
struct SlotSource {
  uint32_t triangle = 0;
  std::array<int, 3> corner{};
};

// One mesh's way from its primitives to the engine's wedge mesh and back.
class WedgeMeshBuilder {
 public:
  WedgeMeshBuilder(const SceneMesh& mesh, const MeshTopology& topology,
                   const AttributeWeights& weights)
      : mesh_(mesh), topology_(topology), weights_(weights) {
    for (uint32_t point = 0; point < topology.mesh.positions.size(); ++point)
      point_of_position_.emplace(key_of(topology.mesh.positions[point]), point);
    for (uint32_t p = 0; p < mesh.primitives.size(); ++p)
      for (const std::array<uint32_t, 3>& t : primitive_triangles(mesh.primitives[p]))
        local_triangles_.push_back(t);
  }

  // The wedge mesh of `repaired` (the topology after prepare_mesh()).
  Result<WedgeMesh> build(const TriangleMesh& repaired) {
    LODBAKE_RETURN_IF_ERROR(map_slots(repaired));
    // A primitive's vertices with the same point and bytes are one wedge:
    // each vertex's first such vertex.
    std::vector<std::vector<uint32_t>> first_alike(mesh_.primitives.size());
    for (uint32_t p = 0; p < mesh_.primitives.size(); ++p) {
      const std::vector<uint32_t>& points = mesh_.point_of_vertex[p];
      std::unordered_map<std::string, uint32_t> first;
      first_alike[p].resize(points.size());
      for (uint32_t v = 0; v < points.size(); ++v) {
        std::string key = vertex_bytes(mesh_.primitives[p], v);
        key.append(reinterpret_cast<const char*>(&points[v]), sizeof(uint32_t));
        first_alike[p][v] = first.emplace(std::move(key), v).first->second;
      }
    }
    WedgeMesh out;
    out.uv_sets = uv_sets();
    out.points.reserve(repaired.positions.size());
    for (const Vec3f& p : repaired.positions)
      out.points.push_back({p[0], p[1], p[2]});
    out.triangles = repaired.triangles;
    out.value_offset.push_back(0);
    // The wedges at each point of `repaired`: a few at most.
    std::vector<std::vector<uint32_t>> wedges_at(repaired.positions.size());
    for (size_t f = 0; f < repaired.triangles.size(); ++f) {
      const SlotSource& s = slots_[f];
      const uint32_t p = topology_.primitive_of_triangle[s.triangle];
      const ScenePrimitive& prim = mesh_.primitives[p];
      std::array<uint32_t, 3> corners{};
      for (int k = 0; k < 3; ++k) {
        const uint32_t vertex = first_alike[p][local_triangles_[s.triangle][s.corner[k]]];
        const uint32_t point = repaired.triangles[f][k];
        uint32_t wedge = kNoVertex;
        for (uint32_t w : wedges_at[point])
          if (wedge_primitive_[w] == p && wedge_vertex_[w] == vertex) wedge = w;
        if (wedge == kNoVertex) {
          wedge = static_cast<uint32_t>(out.wedge_point.size());
          wedges_at[point].push_back(wedge);
          out.wedge_point.push_back(point);
          wedge_primitive_.push_back(p);
          wedge_vertex_.push_back(vertex);
          append_values(prim, vertex, &out);
        }
        corners[k] = wedge;
      }
      out.corner_wedge.push_back(corners);
    }
    return out;
  }

  // The (primitive, vertex) of each wedge of the last build().
  const std::vector<uint32_t>& wedge_primitive() const { return wedge_primitive_; }
  const std::vector<uint32_t>& wedge_vertex() const { return wedge_vertex_; }

  // The mesh's primitives for `triangles` (indices into `positions`), whose
  // corners use the wedges `corners` of the table (wedge_primitive,
  // wedge_vertex). A corner away from its wedge's vertex (a wedge moved by
  // a permissive collapse) keeps the wedge's values at its own position;
  // `moved` counts those wedges. The table may come from a file: every
  // index is checked.
  Result<std::vector<ScenePrimitive>> assemble(const std::vector<Vec3f>& positions,
                                               const std::vector<Triangle>& triangles,
                                               const std::vector<std::array<uint32_t, 3>>& corners,
                                               const std::vector<uint32_t>& wedge_primitive,
                                               const std::vector<uint32_t>& wedge_vertex,
                                               const std::vector<uint32_t>& wedge_home,
                                               uint64_t* moved) const {
    const size_t n = mesh_.primitives.size();
    if (corners.size() != triangles.size() || wedge_vertex.size() != wedge_primitive.size() ||
        wedge_home.size() != wedge_primitive.size())
      return invalid_input("the wedges do not match the triangles");
    struct Built {
      std::vector<uint32_t> indices;
      // (vertex, the corner's vertex in `positions` when away from home, or -1)
      std::vector<std::pair<uint32_t, int64_t>> sources;
      std::map<std::pair<uint32_t, int64_t>, uint32_t> index_of;
    };
    std::vector<Built> built(n);
    std::vector<uint8_t> counted(wedge_primitive.size(), 0);
    *moved = 0;
    for (size_t f = 0; f < triangles.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t w = corners[f][k];
        const uint32_t at = triangles[f][k];
        if (w >= wedge_primitive.size() || at >= positions.size())
          return invalid_input("triangle " + std::to_string(f) + " has a corner out of range");
        const uint32_t p = wedge_primitive[w], v = wedge_vertex[w];
        if (p >= n || v >= mesh_.point_of_vertex[p].size() ||
            topology_.triangles_per_primitive[p] == 0)
          return invalid_input("wedge " + std::to_string(w) +
                               " is no vertex of a triangle primitive");
        std::pair<uint32_t, int64_t> key{v, -1};
        if (at != wedge_home[w]) {
          key.second = at;
          if (!counted[w]) ++*moved;
          counted[w] = 1;
        }
        Built& b = built[p];
        auto [it, added] = b.index_of.emplace(key, static_cast<uint32_t>(b.sources.size()));
        if (added) b.sources.push_back(key);
        b.indices.push_back(it->second);
      }
    }
    // A wedge at home at each point: where a moved corner's exact position
    // is read from the asset, not from `positions` (a Draco or quantized
    // BASE's are not the asset's).
    std::vector<std::pair<uint32_t, uint32_t>> home_vertex(positions.size(), {kNoVertex, 0});
    for (size_t w = 0; w < wedge_home.size(); ++w)
      if (wedge_home[w] < positions.size() && home_vertex[wedge_home[w]].first == kNoVertex &&
          wedge_primitive[w] < n &&
          wedge_vertex[w] < mesh_.point_of_vertex[wedge_primitive[w]].size())
        home_vertex[wedge_home[w]] = {wedge_primitive[w], wedge_vertex[w]};
    std::vector<ScenePrimitive> out;
    for (uint32_t p = 0; p < n; ++p) {
      const ScenePrimitive& in = mesh_.primitives[p];
      if (topology_.triangles_per_primitive[p] == 0) {
        out.push_back(in);  // points and lines are kept as they are
        continue;
      }
      if (built[p].indices.empty()) continue;  // simplified away at this level
      ScenePrimitive prim;
      prim.mode = PrimitiveMode::kTriangles;
      prim.material = in.material;
      prim.extras = in.extras;
      prim.extensions = in.extensions;
      prim.indices = std::move(built[p].indices);
      for (const SceneAttribute& a : in.attributes)
        prim.attributes.push_back(gather(a, built[p].sources, positions, home_vertex));
      for (const std::vector<SceneAttribute>& target : in.targets) {
        std::vector<SceneAttribute> t;
        for (const SceneAttribute& a : target) {
          SceneAttribute g = a;
          g.data = select(a.data, built[p].sources);
          t.push_back(std::move(g));
        }
        prim.targets.push_back(std::move(t));
      }
      out.push_back(std::move(prim));
    }
    return out;
  }

 private:
  // Triangle f of `repaired` is an input triangle.
  Status map_slots(const TriangleMesh& repaired) {
    slots_.resize(repaired.triangles.size());
    if (repaired.triangles == topology_.mesh.triangles &&
        repaired.positions == topology_.mesh.positions) {
      // Nothing repaired (the common case): triangle f is triangle f.
      for (uint32_t f = 0; f < slots_.size(); ++f)
        slots_[f] = {f, {0, 1, 2}};
      return Status::ok();
    }
    std::unordered_map<TriangleKey, std::pair<uint32_t, int>, TriangleKeyHash> triangle_of_key;
    for (uint32_t t = 0; t < topology_.mesh.triangles.size(); ++t) {
      const Triangle& tri = topology_.mesh.triangles[t];
      int r = 0;
      const TriangleKey key = rotated_key(key_of(topology_.mesh.positions[tri[0]]),
                                          key_of(topology_.mesh.positions[tri[1]]),
                                          key_of(topology_.mesh.positions[tri[2]]), &r);
      triangle_of_key.emplace(key, std::make_pair(t, r));
    }
    for (size_t f = 0; f < repaired.triangles.size(); ++f) {
      const Triangle& t = repaired.triangles[f];
      const PositionKey k[3] = {key_of(repaired.positions[t[0]]), key_of(repaired.positions[t[1]]),
                                key_of(repaired.positions[t[2]])};
      int r = 0;
      auto found = triangle_of_key.find(rotated_key(k[0], k[1], k[2], &r));
      bool reversed = false;
      if (found == triangle_of_key.end()) {
        // The repair may have turned the triangle to orient the mesh.
        found = triangle_of_key.find(rotated_key(k[0], k[2], k[1], &r));
        reversed = true;
      }
      if (found == triangle_of_key.end())
        return runtime_error("face " + std::to_string(f) +
                             " of the repaired mesh is no triangle of the input");
      const int r_input = found->second.second;
      SlotSource& s = slots_[f];
      s.triangle = found->second.first;
      // Key position i is slot corner (i + r) % 3 (slot order, or a, c, b
      // when reversed) and input corner (i + r_input) % 3.
      const int slot_order[3] = {0, reversed ? 2 : 1, reversed ? 1 : 2};
      for (int i = 0; i < 3; ++i)
        s.corner[slot_order[(i + r) % 3]] = (i + r_input) % 3;
    }
    return Status::ok();
  }

  // Every stream's bytes of one vertex (its morph targets' too): two
  // vertices of a primitive with the same bytes at a point are one wedge.
  static std::string vertex_bytes(const ScenePrimitive& prim, uint32_t v) {
    std::string bytes;
    auto add = [&](const AccessorData& d) {
      const size_t size = d.element_size();
      bytes.append(reinterpret_cast<const char*>(d.bytes.data()) + size_t{v} * size, size);
    };
    for (const SceneAttribute& a : prim.attributes)
      add(a.data);
    for (const std::vector<SceneAttribute>& target : prim.targets)
      for (const SceneAttribute& a : target)
        add(a.data);
    return bytes;
  }

  // How many texture coordinate sets the fold check reads: up to the
  // highest TEXCOORD_n any primitive of the mesh has, at least one.
  uint32_t uv_sets() const {
    uint32_t sets = 1;
    for (const ScenePrimitive& prim : mesh_.primitives)
      for (uint32_t set = sets; set < WedgeMesh::kMaxUvSets; ++set)
        if (prim.find("TEXCOORD_" + std::to_string(set)) != nullptr) sets = set + 1;
    return sets;
  }

  double weight_of(const std::string& semantic) const {
    if (semantic == "NORMAL") return weights_.normal;
    if (semantic == "TANGENT") return weights_.tangent;
    if (semantic.rfind("TEXCOORD_", 0) == 0) return weights_.texcoord;
    if (semantic.rfind("COLOR_", 0) == 0) return weights_.color;
    return 0;
  }

  // The weighted error values of a new wedge, and its UV and normal.
  void append_values(const ScenePrimitive& prim, uint32_t v, WedgeMesh* out) const {
    for (const SceneAttribute& a : prim.attributes) {
      const double weight = weight_of(a.semantic);
      if (weight == 0) continue;
      // TANGENT's w is a handedness sign, not a value to interpolate.
      const uint32_t components = a.semantic == "TANGENT" ? 3 : a.data.components();
      for (uint32_t c = 0; c < components; ++c)
        out->values.push_back(static_cast<float>(weight * float_value(a.data, v, c)));
    }
    out->value_offset.push_back(static_cast<uint32_t>(out->values.size()));
    uint8_t has_uv = 0;
    for (uint32_t set = 0; set < out->uv_sets; ++set) {
      const SceneAttribute* uv = prim.find("TEXCOORD_" + std::to_string(set));
      const bool present = uv != nullptr && uv->data.components() == 2;
      has_uv |= static_cast<uint8_t>(present) << set;
      out->uv.push_back(present ? Vec2f{float_value(uv->data, v, 0), float_value(uv->data, v, 1)}
                                : Vec2f{});
    }
    out->has_uv.push_back(has_uv);
    const SceneAttribute* normal = prim.find("NORMAL");
    out->has_normal.push_back(normal != nullptr && normal->data.components() == 3);
    out->normal.push_back(out->has_normal.back() ? Vec3f{float_value(normal->data, v, 0),
                                                         float_value(normal->data, v, 1),
                                                         float_value(normal->data, v, 2)}
                                                 : Vec3f{});
  }

  static AccessorData select(const AccessorData& in,
                             const std::vector<std::pair<uint32_t, int64_t>>& sources) {
    AccessorData out = in;
    const size_t size = in.element_size();
    out.count = static_cast<uint32_t>(sources.size());
    out.bytes.resize(sources.size() * size);
    for (size_t i = 0; i < sources.size(); ++i)
      std::memcpy(out.bytes.data() + i * size, in.bytes.data() + size_t{sources[i].first} * size,
                  size);
    return out;
  }

  SceneAttribute gather(const SceneAttribute& a,
                        const std::vector<std::pair<uint32_t, int64_t>>& sources,
                        const std::vector<Vec3f>& positions,
                        const std::vector<std::pair<uint32_t, uint32_t>>& home_vertex) const {
    SceneAttribute out = a;
    out.data = select(a.data, sources);
    if (a.semantic != "POSITION") return out;
    // A moved wedge sits at another point: its position, the asset's own
    // where a vertex at home there stores it alike.
    const size_t size = a.data.element_size();
    for (size_t i = 0; i < sources.size(); ++i) {
      if (sources[i].second < 0) continue;
      const size_t at = static_cast<size_t>(sources[i].second);
      if (const auto [hp, hv] = home_vertex[at]; hp != kNoVertex) {
        const SceneAttribute* home = mesh_.primitives[hp].find("POSITION");
        if (home != nullptr && home->data.component_type == a.data.component_type &&
            home->data.normalized == a.data.normalized &&
            home->data.components() == a.data.components() && hv < home->data.count) {
          std::memcpy(out.data.bytes.data() + i * size, home->data.bytes.data() + size_t{hv} * size,
                      size);
          continue;
        }
      }
      const Vec3f& position = positions[at];
      if (a.data.component_type == ComponentType::kFloat && a.data.components() == 3) {
        std::memcpy(out.data.bytes.data() + i * size, position.data(), size);
        continue;
      }
      auto point = point_of_position_.find(key_of(position));
      if (point == point_of_position_.end()) continue;
      if (const std::optional<std::pair<uint32_t, uint32_t>> same =
              same_type_vertex(point->second, a.data)) {
        const AccessorData& from = mesh_.primitives[same->first].find("POSITION")->data;
        std::memcpy(out.data.bytes.data() + i * size,
                    from.bytes.data() + size_t{same->second} * size, size);
      }
      // Otherwise (quantized differently in every primitive at that point,
      // or a quantized progressive mesh's point) the corner keeps its own
      // position; documented in docs/simplify.md.
    }
    return out;
  }

  // A vertex of any primitive at `point` whose POSITION is stored like `like`.
  std::optional<std::pair<uint32_t, uint32_t>> same_type_vertex(uint32_t point,
                                                                const AccessorData& like) const {
    if (vertices_at_.empty()) {  // built on the first need: moved quantized positions are rare
      for (uint32_t p = 0; p < mesh_.primitives.size(); ++p) {
        const std::vector<uint32_t>& points = mesh_.point_of_vertex[p];
        for (uint32_t v = 0; v < points.size(); ++v)
          vertices_at_[{p, points[v]}].push_back(v);
      }
    }
    for (uint32_t q = 0; q < mesh_.primitives.size(); ++q) {
      const SceneAttribute* pos = mesh_.primitives[q].find("POSITION");
      if (pos == nullptr || pos->data.component_type != like.component_type ||
          pos->data.normalized != like.normalized || pos->data.type != like.type)
        continue;
      auto at = vertices_at_.find({q, point});
      if (at == vertices_at_.end()) continue;
      return std::make_pair(q, at->second.front());
    }
    return std::nullopt;
  }

  const SceneMesh& mesh_;
  const MeshTopology& topology_;
  const AttributeWeights& weights_;
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> point_of_position_;
  std::vector<std::array<uint32_t, 3>> local_triangles_;  // per topology triangle
  // (primitive, point) -> its vertices there; filled by same_type_vertex().
  mutable std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> vertices_at_;
  std::vector<SlotSource> slots_;
  std::vector<uint32_t> wedge_primitive_;  // per engine wedge
  std::vector<uint32_t> wedge_vertex_;
};

std::string mesh_name(uint32_t m) {
  return "mesh " + std::to_string(m);
}

Status in_mesh(uint32_t m, const Status& status) {
  return Status(status.kind(), mesh_name(m) + ": " + status.message());
}

// One mesh made ready for the engine: its welded topology, repaired as the
// load options say, and its wedge mesh. Not movable: the builder refers to
// the topology.
struct PreparedMesh {
  PreparedMesh(const SceneMesh& mesh, const AttributeWeights& weights)
      : topology(mesh_topology(mesh)), builder(mesh, topology, weights) {}
  MeshTopology topology;
  LoadedMesh loaded;
  WedgeMeshBuilder builder;
  WedgeMesh wedges;
};

// Null when the mesh has no triangle.
Result<std::unique_ptr<PreparedMesh>> prepare(const SceneMesh& mesh, uint32_t m,
                                              const SceneLodOptions& options) {
  auto prepared = std::make_unique<PreparedMesh>(mesh, options.weights);
  if (prepared->topology.mesh.triangles.empty()) return std::unique_ptr<PreparedMesh>();
  prepared->loaded.mesh = prepared->topology.mesh;
  LoadOptions load = options.load;
  load.drop_unreferenced = true;
  load.per_vertex_attributes = false;
  if (Status ok = prepare_mesh(load, &prepared->loaded); !ok.is_ok()) return in_mesh(m, ok);
  Result<WedgeMesh> wedges = prepared->builder.build(prepared->loaded.mesh);
  if (!wedges.is_ok()) return in_mesh(m, wedges.status());
  prepared->wedges = std::move(wedges).value();
  return prepared;
}

WedgeCollapseOptions engine_options(const SceneLodOptions& options) {
  WedgeCollapseOptions run;
  run.max_error = options.simplify.max_error;
  run.boundary_weight = options.simplify.boundary_weight;
  run.lock_border = options.simplify.lock_border;
  run.permissive = options.simplify.permissive;
  run.seam_release = options.simplify.seam_release;
  run.max_normal_change_degrees = options.simplify.max_normal_change_degrees;
  run.progress = options.simplify.progress;
  return run;
}

// Each level's target triangle count, in the order of `ratios` (one when
// it is empty: the simplify options' target, 0 without one).
std::vector<uint64_t> level_targets(const SceneLodOptions& options, uint64_t triangles) {
  std::vector<uint64_t> targets;
  for (double r : options.ratios)
    targets.push_back(static_cast<uint64_t>(r * static_cast<double>(triangles)));
  if (targets.empty()) {
    uint64_t target = 0;
    if (options.simplify.target_ratio)
      target =
          static_cast<uint64_t>(*options.simplify.target_ratio * static_cast<double>(triangles));
    if (options.simplify.target_triangles)
      target = std::max(target, *options.simplify.target_triangles);
    targets.push_back(target);
  }
  return targets;
}

Status check_placement(const SceneLodOptions& options) {
  if (options.simplify.placement != Placement::kHalf)
    return Status(ErrorKind::kUsage,
                  "an asset is simplified with half-edge collapses only (its corners keep "
                  "their attributes at the input's points)");
  return Status::ok();
}

}  // namespace

Result<SceneLods> simplify_scene(const Scene& scene, const SceneLodOptions& options) {
  LODBAKE_RETURN_IF_ERROR(check_placement(options));
  const size_t levels = options.ratios.empty() ? 1 : options.ratios.size();
  SceneLods result;
  result.levels.assign(levels, scene);
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<PreparedMesh> prepared,
                             prepare(scene.meshes[m], m, options));
    if (!prepared) continue;
    // The engine takes its targets in decreasing order; the levels keep
    // the order of `ratios`.
    const std::vector<uint64_t> targets =
        level_targets(options, prepared->loaded.mesh.triangle_count());
    std::vector<size_t> order(targets.size());
    for (size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return targets[a] > targets[b]; });
    WedgeCollapseOptions run = engine_options(options);
    for (size_t i : order)
      run.targets.push_back(targets[i]);
    Result<WedgeCollapseResult> collapsed = collapse_wedges(prepared->wedges, run);
    if (!collapsed.is_ok()) return in_mesh(m, collapsed.status());

    MeshLodReport report;
    report.mesh = m;
    report.input_triangles = prepared->topology.mesh.triangles.size();
    report.repaired = prepared->loaded.repair.has_value();
    report.blocked = collapsed.value().blocked;
    report.lod_triangles.resize(levels);
    report.lod_targets = targets;
    for (size_t i = 0; i < order.size(); ++i) {
      const size_t level = order[i];
      const WedgeLevel& engine_level = collapsed.value().levels[i];
      uint64_t moved = 0;
      Result<std::vector<ScenePrimitive>> primitives = prepared->builder.assemble(
          prepared->loaded.mesh.positions, engine_level.triangles, engine_level.corner_wedge,
          prepared->builder.wedge_primitive(), prepared->builder.wedge_vertex(),
          prepared->wedges.wedge_point, &moved);
      if (!primitives.is_ok()) return in_mesh(m, primitives.status());
      SceneMesh& out = result.levels[level].meshes[m];
      out.primitives = std::move(primitives).value();
      out.point_of_vertex.clear();
      out.point_count = 0;
      report.lod_triangles[level] = engine_level.triangles.size();
      if (i + 1 == order.size()) report.moved_wedges = moved;
    }
    result.meshes.push_back(std::move(report));
  }
  return result;
}

Result<std::vector<MeshPm>> scene_progressive_meshes(const Scene& scene,
                                                     const SceneLodOptions& options) {
  LODBAKE_RETURN_IF_ERROR(check_placement(options));
  std::vector<MeshPm> out;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<PreparedMesh> prepared,
                             prepare(scene.meshes[m], m, options));
    if (!prepared) continue;
    const std::vector<uint64_t> targets =
        level_targets(options, prepared->loaded.mesh.triangle_count());
    WedgeCollapseOptions run = engine_options(options);
    run.targets = {*std::min_element(targets.begin(), targets.end())};
    run.record = true;
    Result<WedgeCollapseResult> collapsed = collapse_wedges(prepared->wedges, run);
    if (!collapsed.is_ok()) return in_mesh(m, collapsed.status());
    Result<WedgePm> recorded = record_wedge_pm(prepared->wedges, collapsed.value());
    if (!recorded.is_ok()) return in_mesh(m, recorded.status());
    MeshPm pm;
    pm.mesh = m;
    pm.repaired = prepared->loaded.repair.has_value();
    pm.blocked = collapsed.value().blocked;
    pm.pm = std::move(recorded.value().pm);
    pm.wedges = std::move(recorded.value().wedges);
    pm.wedges.wedge_primitive = prepared->builder.wedge_primitive();
    pm.wedges.wedge_vertex = prepared->builder.wedge_vertex();
    out.push_back(std::move(pm));
  }
  return out;
}

Result<std::vector<MeshCornerWedges>> scene_corner_wedges(const Scene& scene,
                                                          const LoadOptions& load) {
  SceneLodOptions options;
  options.load = load;
  std::vector<MeshCornerWedges> out;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<PreparedMesh> prepared,
                             prepare(scene.meshes[m], m, options));
    if (!prepared) continue;
    MeshCornerWedges corners;
    corners.mesh = m;
    corners.topology = std::move(prepared->loaded.mesh);
    corners.corner_wedge = std::move(prepared->wedges.corner_wedge);
    corners.wedge_point = std::move(prepared->wedges.wedge_point);
    corners.wedge_primitive = prepared->builder.wedge_primitive();
    corners.wedge_vertex = prepared->builder.wedge_vertex();
    out.push_back(std::move(corners));
  }
  return out;
}

Result<PmWedges> wedges_of_pm(const ProgressiveMesh& pm, const MeshCornerWedges& corners) {
  if (pm.full_vertex_count() != corners.topology.vertex_count())
    return runtime_error(mesh_name(corners.mesh) + ": the progressive mesh has " +
                         std::to_string(pm.full_vertex_count()) + " vertices, the mesh " +
                         std::to_string(corners.topology.vertex_count()));
  Result<PmWedges> wedges =
      assign_pm_wedges(pm, corners.topology.triangles, corners.corner_wedge, corners.wedge_point);
  if (!wedges.is_ok()) return in_mesh(corners.mesh, wedges.status());
  wedges.value().wedge_primitive = corners.wedge_primitive;
  wedges.value().wedge_vertex = corners.wedge_vertex;
  return wedges;
}

Result<std::vector<ScenePrimitive>> primitives_at_level(
    const SceneMesh& mesh, const TriangleMesh& level,
    const std::vector<std::array<uint32_t, 3>>& corners, const PmWedges& wedges) {
  const MeshTopology topology = mesh_topology(mesh);
  const WedgeMeshBuilder assembler(mesh, topology, AttributeWeights{});
  uint64_t moved = 0;
  return assembler.assemble(level.positions, level.triangles, corners, wedges.wedge_primitive,
                            wedges.wedge_vertex, wedges.wedge_home, &moved);
}

}  // namespace lodbake
