#include "lib/scene/scene_lods.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>
#include <unordered_map>
#include <utility>

#include "formats/scene/accessor_values.h"
#include "lib/scene/scene_topology.h"
#include "lib/simplify/lod_chain.h"
#include "lib/simplify/pm_replay.h"

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

// For one face slot of the progressive mesh: the input triangle it is and,
// for each of its corners, which corner of that input triangle.
struct SlotSource {
  uint32_t triangle = 0;
  std::array<int, 3> corner{};
};

// One mesh's way from the progressive mesh's faces back to its primitives.
class MeshRebuilder {
 public:
  MeshRebuilder(const SceneMesh& mesh, const MeshTopology& topology)
      : mesh_(mesh), topology_(topology) {
    for (uint32_t point = 0; point < topology.mesh.positions.size(); ++point)
      point_of_position_.emplace(key_of(topology.mesh.positions[point]), point);
    for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
      for (const std::array<uint32_t, 3>& t : primitive_triangles(mesh.primitives[p]))
        local_triangles_.push_back(t);
      const std::vector<uint32_t>& points = mesh.point_of_vertex[p];
      for (uint32_t v = 0; v < points.size(); ++v)
        vertices_at_[{p, points[v]}].push_back(v);
    }
    for (uint32_t t = 0; t < topology.mesh.triangles.size(); ++t) {
      const Triangle& tri = topology.mesh.triangles[t];
      int r = 0;
      const TriangleKey key = rotated_key(key_of(topology.mesh.positions[tri[0]]),
                                          key_of(topology.mesh.positions[tri[1]]),
                                          key_of(topology.mesh.positions[tri[2]]), &r);
      triangle_of_key_.emplace(key, std::make_pair(t, r));
    }
  }

  // Slot f of `full` (the fully refined mesh in PM ids) is an input triangle.
  Status map_slots(const TriangleMesh& full) {
    slots_.resize(full.triangles.size());
    for (size_t f = 0; f < full.triangles.size(); ++f) {
      const Triangle& t = full.triangles[f];
      const PositionKey k[3] = {key_of(full.positions[t[0]]), key_of(full.positions[t[1]]),
                                key_of(full.positions[t[2]])};
      int r = 0;
      auto found = triangle_of_key_.find(rotated_key(k[0], k[1], k[2], &r));
      bool reversed = false;
      if (found == triangle_of_key_.end()) {
        // The repair may have turned the triangle to orient the mesh.
        found = triangle_of_key_.find(rotated_key(k[0], k[2], k[1], &r));
        reversed = true;
      }
      if (found == triangle_of_key_.end())
        return runtime_error("face " + std::to_string(f) +
                             " of the simplified mesh is no triangle of the input");
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

  // The mesh's primitives at a level (PM ids, the first slots).
  Result<std::vector<ScenePrimitive>> primitives_at(const TriangleMesh& level,
                                                    uint64_t* borrowed) const {
    const size_t n = mesh_.primitives.size();
    struct Built {
      std::vector<uint32_t> indices;
      std::vector<std::pair<uint32_t, int64_t>> sources;  // (vertex, point for the position or -1)
      std::map<std::pair<uint32_t, int64_t>, uint32_t> index_of;
    };
    std::vector<Built> built(n);
    for (size_t f = 0; f < level.triangles.size(); ++f) {
      const SlotSource& s = slots_[f];
      const uint32_t p = topology_.primitive_of_triangle[s.triangle];
      const std::array<uint32_t, 3>& local = local_triangles_[s.triangle];
      for (int k = 0; k < 3; ++k) {
        auto point = point_of_position_.find(key_of(level.positions[level.triangles[f][k]]));
        if (point == point_of_position_.end())
          return runtime_error("a vertex of the simplified mesh is no point of the input");
        const uint32_t own = local[s.corner[k]];
        std::pair<uint32_t, int64_t> source = wedge(p, own, point->second, borrowed);
        auto [it, added] =
            built[p].index_of.emplace(source, static_cast<uint32_t>(built[p].sources.size()));
        if (added) built[p].sources.push_back(source);
        built[p].indices.push_back(it->second);
      }
    }
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
        prim.attributes.push_back(gather(a, built[p].sources));
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
  // The vertex whose values a corner of primitive p, formerly at its own
  // vertex `own`, takes at `point`; with the point to take the position
  // from when the vertex is not at it (-1 otherwise).
  std::pair<uint32_t, int64_t> wedge(uint32_t p, uint32_t own, uint32_t point,
                                     uint64_t* borrowed) const {
    if (mesh_.point_of_vertex[p][own] == point) return {own, -1};
    auto at = vertices_at_.find({p, point});
    if (at == vertices_at_.end()) {
      ++*borrowed;
      return {own, point};
    }
    const std::vector<uint32_t>& candidates = at->second;
    uint32_t best = candidates.front();
    double best_distance = -1;
    for (uint32_t c : candidates) {
      const double d = distance(mesh_.primitives[p], own, c);
      if (best_distance < 0 || d < best_distance) {
        best = c;
        best_distance = d;
      }
    }
    return {best, -1};
  }

  static double distance(const ScenePrimitive& prim, uint32_t a, uint32_t b) {
    double sum = 0;
    for (const SceneAttribute& s : prim.attributes) {
      if (s.semantic == "POSITION") continue;
      for (uint32_t c = 0; c < s.data.components(); ++c) {
        const double d = float_value(s.data, a, c) - float_value(s.data, b, c);
        sum += d * d;
      }
    }
    return sum;
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
                        const std::vector<std::pair<uint32_t, int64_t>>& sources) const {
    SceneAttribute out = a;
    out.data = select(a.data, sources);
    if (a.semantic != "POSITION") return out;
    // A borrowed corner sits at another primitive's point: its position.
    const size_t size = a.data.element_size();
    for (size_t i = 0; i < sources.size(); ++i) {
      if (sources[i].second < 0) continue;
      const Vec3f& position = topology_.mesh.positions[sources[i].second];
      if (a.data.component_type == ComponentType::kFloat && a.data.components() == 3) {
        std::memcpy(out.data.bytes.data() + i * size, position.data(), size);
      } else if (const std::optional<std::pair<uint32_t, uint32_t>> same =
                     same_type_vertex(static_cast<uint32_t>(sources[i].second), a.data)) {
        const AccessorData& from = mesh_.primitives[same->first].find("POSITION")->data;
        std::memcpy(out.data.bytes.data() + i * size,
                    from.bytes.data() + size_t{same->second} * size, size);
      }
      // Otherwise (quantized differently in every primitive at that point)
      // the corner keeps its own position; documented in docs/simplify.md.
    }
    return out;
  }

  // A vertex of any primitive at `point` whose POSITION is stored like `like`.
  std::optional<std::pair<uint32_t, uint32_t>> same_type_vertex(uint32_t point,
                                                                const AccessorData& like) const {
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
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> point_of_position_;
  std::unordered_map<TriangleKey, std::pair<uint32_t, int>, TriangleKeyHash> triangle_of_key_;
  std::vector<std::array<uint32_t, 3>> local_triangles_;  // per topology triangle
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> vertices_at_;  // (prim, point)
  std::vector<SlotSource> slots_;
};

std::string mesh_name(uint32_t m) {
  return "mesh " + std::to_string(m);
}

}  // namespace

Result<SceneLods> simplify_scene(const Scene& scene, const SceneLodOptions& options) {
  if (options.simplify.placement != Placement::kHalf)
    return Status(ErrorKind::kUsage,
                  "an asset is simplified with half-edge collapses only (its corners keep "
                  "their attributes at the input's points)");
  const size_t levels = options.ratios.empty() ? 1 : options.ratios.size();
  SceneLods result;
  result.levels.assign(levels, scene);
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    const MeshTopology topology = mesh_topology(mesh);
    if (topology.mesh.triangles.empty()) continue;
    LoadedMesh loaded;
    loaded.mesh = topology.mesh;
    LoadOptions load = options.load;
    load.drop_unreferenced = true;
    load.per_vertex_attributes = false;
    Status prepared = prepare_mesh(load, &loaded);
    if (!prepared.is_ok()) return Status(prepared.kind(), mesh_name(m) + ": " + prepared.message());
    SimplifyOptions run = options.simplify;
    run.record_pm = true;
    if (!options.ratios.empty())
      run.target_ratio = *std::min_element(options.ratios.begin(), options.ratios.end());
    Result<SimplifyResult> simplified = simplify(loaded.mesh, run);
    if (!simplified.is_ok())
      return Status(simplified.status().kind(),
                    mesh_name(m) + ": " + simplified.status().message());
    const ProgressiveMesh& pm = *simplified.value().pm;
    std::vector<uint64_t> targets;
    const uint64_t triangles = loaded.mesh.triangle_count();
    for (double r : options.ratios)
      targets.push_back(static_cast<uint64_t>(r * static_cast<double>(triangles)));
    if (targets.empty()) targets.push_back(simplified.value().mesh.triangle_count());
    targets.push_back(UINT64_MAX);  // the fully refined mesh, to map face slots
    LODBAKE_ASSIGN_OR_RETURN(std::vector<TriangleMesh> meshes, extract_lods(pm, targets));

    MeshRebuilder rebuilder(mesh, topology);
    Status mapped = rebuilder.map_slots(meshes.back());
    if (!mapped.is_ok()) return Status(mapped.kind(), mesh_name(m) + ": " + mapped.message());
    MeshLodReport report;
    report.mesh = m;
    report.input_triangles = topology.mesh.triangles.size();
    report.repaired = loaded.repair.has_value();
    for (size_t level = 0; level < levels; ++level) {
      Result<std::vector<ScenePrimitive>> primitives =
          rebuilder.primitives_at(meshes[level], &report.borrowed_corners);
      if (!primitives.is_ok())
        return Status(primitives.status().kind(),
                      mesh_name(m) + ": " + primitives.status().message());
      SceneMesh& out = result.levels[level].meshes[m];
      out.primitives = std::move(primitives).value();
      out.point_of_vertex.clear();
      out.point_count = 0;
      report.lod_triangles.push_back(meshes[level].triangle_count());
    }
    result.meshes.push_back(std::move(report));
  }
  return result;
}

}  // namespace lodbake
