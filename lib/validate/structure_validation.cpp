// Each check runs the consumer's own code (structure_loading.h and the
// runtimes) from one end of the structure to the other; a failure becomes a
// finding on the section whose data the consumer refused, prefixed with the
// consumer ("mode stream: ..."). Costs grow linearly with the structure
// (docs/tools.md gives them for the dragon).
#include "lib/validate/structure_validation.h"

#include <algorithm>
#include <new>
#include <string>
#include <utility>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/strp.h"
#include "formats/sections/vtre.h"
#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_wedge_check.h"
#include "lib/replay/structure_cross_check.h"
#include "lib/replay/structure_loading.h"
#include "lib/replay/vhier_replay.h"
#include "lib/replay/vtrees_session.h"
#include "lib/replay/vtrees_wedge_check.h"
#include "lib/simplify/pm_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"

namespace lodbake {
namespace {

// Tolerance (pixels) of the coarsening steps: far above any screen.
constexpr float kCoarseTolerance = 1e6f;
// LoDs a SETS check recovers at most on the way down (then back up).
constexpr uint32_t kSetsLods = 33;

class Findings {
 public:
  explicit Findings(std::vector<SectionFinding>* out) : out_(out) {}
  void add(const char* tag, const std::string& consumer, const std::string& message) {
    out_->push_back({tag, consumer + ": " + message});
  }
  // Adds the first of `problems` (with their count) and returns false when
  // there is any.
  bool none(const char* tag, const std::string& consumer, const std::string& where,
            const std::vector<std::string>& problems) {
    if (problems.empty()) return true;
    std::string text = where + ": " + problems.front();
    if (problems.size() > 1) text += " (and " + std::to_string(problems.size() - 1) + " more)";
    add(tag, consumer, text);
    return false;
  }

 private:
  std::vector<SectionFinding>* out_;
};

// A camera that sees the whole sphere.
CameraFrame overview(const BoundingSphere& sphere) {
  CameraFrame frame;
  frame.target = sphere.center;
  frame.eye = sphere.center;
  frame.eye[2] += 3 * sphere.radius;
  return frame;
}

std::string pm_vertices(const PmRefiner& r) {
  return std::to_string(r.vertex_count());
}

// BASE + VSPL: the progressive mesh from the base to the full mesh and
// back, as --extract --lod, mode sets and the tools reading a PM replay it.
void check_pm(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "progressive mesh";
  const Section* base = decoded.find(kBaseTag, group);
  const Section* vspl = decoded.find(kVsplTag, group);
  Result<ProgressiveMesh> pm =
      decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
  if (!pm.is_ok()) return f->add(kVsplTag, who, pm.status().message());
  Result<PmRefiner> created = PmRefiner::create(pm.value());
  if (!created.is_ok()) return f->add(kVsplTag, who, created.status().message());
  PmRefiner& r = created.value();
  while (!r.fully_refined()) {
    const Status s = r.split_next();
    if (!s.is_ok())
      return f->add(kVsplTag, who,
                    "split " + std::to_string(r.applied_splits()) + ": " + s.message());
  }
  Result<TriangleMesh> input = map_to_input(pm.value(), r.mesh());
  if (!input.is_ok()) return f->add(kVsplTag, who, "the full mesh: " + input.status().message());
  while (r.applied_splits() != 0) {
    const Status s = r.collapse_last();
    if (!s.is_ok())
      return f->add(kVsplTag, who, "collapsing at " + pm_vertices(r) + " vertices: " + s.message());
  }
  if (!same_oriented_triangles(r.mesh(), pm.value().base))
    f->add(kVsplTag, who, "collapsing every split does not give BASE's mesh back");
}

// The fundamental cut vertices against the finest mesh (docs/hierarchy.md,
// "Fundamental cut vertices"): every face of it whose corners are not in
// three trees is the wing face of exactly one split, the node s where its
// deepest pair of corners meet, one corner under each child; it is s's
// left wing (left leaf, right leaf, cut_left[s]) or its right wing (right
// leaf, left leaf, cut_right[s]), counter-clockwise. When every split has
// exactly the wings its cut vertices say, every front the refiner and the
// stream can reach splits and collapses as the build did; a cut vertex that
// only works in one order of splits fails here.
std::vector<std::string> wing_problems(const VertexHierarchy& h,
                                       const std::vector<Triangle>& faces) {
  const auto n = static_cast<uint32_t>(h.node_count());
  std::vector<uint32_t> depth(n, 0);
  for (uint32_t v = 0; v < n; ++v) {
    if (h.parent[v] != kNoNode) depth[v] = depth[h.parent[v]] + 1;
  }
  // The meeting node of leaves a and b and the children of it above them,
  // kNoNode when they are in different trees.
  auto meet = [&](uint32_t a, uint32_t b, uint32_t* below_a, uint32_t* below_b) {
    uint32_t pa = kNoNode, pb = kNoNode;
    while (depth[a] > depth[b])
      pa = a, a = h.parent[a];
    while (depth[b] > depth[a])
      pb = b, b = h.parent[b];
    while (a != b) {
      pa = a, a = h.parent[a];
      pb = b, b = h.parent[b];
      if (a == kNoNode || b == kNoNode) return kNoNode;
    }
    *below_a = pa;
    *below_b = pb;
    return a;
  };
  std::vector<uint32_t> left(n, kNoNode), right(n, kNoNode);
  std::vector<uint8_t> left_count(n, 0), right_count(n, 0);
  size_t base_faces = 0;
  for (const Triangle& t : faces) {
    uint32_t best = kNoNode, corner = 0, ca = 0, cb = 0;
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t a = 0, b = 0;
      const uint32_t m = meet(t[k], t[(k + 1) % 3], &a, &b);
      if (m != kNoNode && (best == kNoNode || depth[m] > depth[best])) {
        best = m, corner = k, ca = a, cb = b;
      }
    }
    if (best == kNoNode) {
      ++base_faces;
      continue;
    }
    const uint32_t z = t[(corner + 2) % 3];
    const uint32_t first = h.first_child[best];
    if (ca == first && cb == first + 1) {
      left[best] = z;
      left_count[best] = static_cast<uint8_t>(std::min(left_count[best] + 1, 2));
    } else {
      right[best] = z;
      right_count[best] = static_cast<uint8_t>(std::min(right_count[best] + 1, 2));
    }
  }
  std::vector<std::string> problems;
  for (uint32_t s = 0; s < n && problems.empty(); ++s) {
    if (h.is_leaf(s)) continue;
    const bool lw = h.cut_left[s] != kNoNode, rw = h.cut_right[s] != kNoNode;
    if (left_count[s] != lw || (lw && left[s] != h.cut_left[s]) || right_count[s] != rw ||
        (rw && right[s] != h.cut_right[s])) {
      problems.push_back("the cut vertices of node " + std::to_string(s) +
                         " are not the corners of its wing faces");
    }
  }
  if (problems.empty() && base_faces != h.base.triangle_count()) {
    problems.push_back(std::to_string(base_faces) + " faces of the finest mesh join three trees, " +
                       "BASE has " + std::to_string(h.base.triangle_count()) + " triangles");
  }
  return problems;
}

// Mode vhier: every node split (with the splits it depends on) to the
// leaves, then everything collapsed back to the roots.
void check_vhier(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "mode vhier";
  Result<VhierStructure> loaded = load_vhier_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kVhieTag, who, loaded.status().message());
  const VertexHierarchy& h = *loaded.value().h;
  SelectiveRefiner& r = *loaded.value().refiner;
  if (!f->none(kVhieTag, who, "the base mesh", check_vhier_mesh(r))) return;
  // An asset's hierarchy: every corner of the base and finest fronts has a
  // wedge of one primitive.
  auto wedge_problems = [&loaded, &r] {
    const VhierStructure& l = loaded.value();
    return l.front ? check_vhier_wedges(r, *l.front, *l.wedges) : std::vector<std::string>();
  };
  if (!f->none(kWedgTag, who, "the base mesh's corners", wedge_problems())) return;
  // Children come after their parent: one pass splits down to the leaves.
  for (uint32_t node = 0; node < h.node_count(); ++node) {
    if (h.is_leaf(node) || !r.is_active(node)) continue;
    const Status s = r.split_with_dependencies(node);
    if (!s.is_ok()) return f->add(kVhieTag, who, "refining every node: " + s.message());
  }
  size_t leaves = 0;
  for (uint32_t node = 0; node < h.node_count(); ++node)
    leaves += h.is_leaf(node);
  if (r.front_size() != leaves) {
    return f->add(kVhieTag, who,
                  "refining every node ends with " + std::to_string(r.front_size()) +
                      " active nodes, not the " + std::to_string(leaves) + " leaves");
  }
  if (!f->none(kVhieTag, who, "the finest mesh", check_vhier_mesh(r))) return;
  if (!f->none(kWedgTag, who, "the finest mesh's corners", wedge_problems())) return;
  if (!f->none(kVhieTag, who, "the finest mesh", wing_problems(h, r.triangles()))) return;
  const Status s = r.collapse_to_base();
  if (!s.is_ok()) return f->add(kVhieTag, who, "collapsing back to the roots: " + s.message());
  if (!f->none(kVhieTag, who, "back at the roots", check_vhier_mesh(r))) return;
  if (r.front_size() != h.root_count() || r.triangle_count() != h.base.triangle_count())
    f->add(kVhieTag, who, "collapsing every node does not give BASE's mesh back");
}

// Mode stream: the server streams every split (tolerance 0), the client
// applies them, then coarsens back with a tolerance no view asks for.
void check_stream(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "mode stream";
  Result<StreamStructure> loaded = load_stream_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kVhieTag, who, loaded.status().message());
  const StreamHierarchy& db = *loaded.value().db;
  StreamReplayOptions options;
  options.tolerance_pixels = 0;
  Result<StreamSession> created = StreamSession::create(db, options);
  if (!created.is_ok()) return f->add(kVhieTag, who, created.status().message());
  StreamSession& session = created.value();
  const CameraFrame camera = overview(db.sphere);
  Result<StreamFrameStats> fine = session.frame(camera, db.sphere);
  if (!fine.is_ok())
    return f->add(kVhieTag, who, "streaming every split: " + fine.status().message());
  if (fine.value().missing != 0) {
    return f->add(
        kVhieTag, who,
        "streaming every split leaves " + std::to_string(fine.value().missing) + " splits missing");
  }
  if (!f->none(kVhieTag, who, "the finest mesh", check_vhier_mesh(session.client().refiner())))
    return;
  // An asset's stream: the client's corners are the server front's.
  const StreamStructure& st = loaded.value();
  auto wedge_problems = [&] {
    return st.front ? check_stream_wedges(session.client(), db, *st.front, *st.wedges)
                    : std::vector<std::string>();
  };
  if (!f->none(kWedgTag, who, "the finest mesh's corners", wedge_problems())) return;
  const ViewRequest coarse =
      view_request_for(camera, options.viewport, options.viewport.near_fraction * db.sphere.radius,
                       kCoarseTolerance);
  Result<StreamFrameStats> back = session.step(coarse);
  if (!back.is_ok()) return f->add(kVhieTag, who, "coarsening: " + back.status().message());
  if (!f->none(kVhieTag, who, "coarsened", check_vhier_mesh(session.client().refiner()))) return;
  f->none(kWedgTag, who, "the coarsened mesh's corners", wedge_problems());
}

// Mode vtrees: the database over the hierarchy, then a session sending
// every split; the client's list and triangles must be the server's, and
// on an asset's trees every corner's wedge the hierarchy front's.
void check_vtrees(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "mode vtrees";
  Result<VtreesStructure> loaded = load_vtrees_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kVtreTag, who, loaded.status().message());
  const VtreesDatabase& db = *loaded.value().db;
  const VertexTrees& trees = *loaded.value().trees;
  VtreesReplayOptions options;
  options.tolerance_pixels = 0;
  Result<VtreesSession> created = VtreesSession::create(db, options);
  if (!created.is_ok()) return f->add(kVtreTag, who, created.status().message());
  VtreesSession& session = created.value();
  const CameraFrame camera = overview(db.sphere);
  const ViewRequest coarse =
      view_request_for(camera, options.viewport, options.viewport.near_fraction * db.sphere.radius,
                       kCoarseTolerance);
  for (int step = 0; step < 2; ++step) {
    const std::string where = step == 0 ? "sending every split" : "coarsening";
    Result<VtreesFrameStats> got =
        step == 0 ? session.frame(camera, db.sphere) : session.step(coarse);
    if (!got.is_ok()) return f->add(kVtreTag, who, where + ": " + got.status().message());
    const VisibleVertexList& list = session.server().list();
    for (uint32_t v = 0; v < trees.positions.size(); ++v) {
      if (session.client().visible_node(v) != list.visible_node(v)) {
        return f->add(kVtreTag, who,
                      where + ": the client's visible node of vertex " + std::to_string(v) +
                          " is not the server's");
      }
    }
    if (sorted_canonical(session.triangles()) != sorted_canonical(list.triangles())) {
      return f->add(kVtreTag, who,
                    where + ": the client's triangles are not the trees' own selection");
    }
    const VtreesStructure& st = loaded.value();
    if (st.reference &&
        !f->none(kWedgTag, who, where + ": the client's corners",
                 check_vtrees_wedges(session.client(), *st.reference, *st.wedges))) {
      return;
    }
  }
}

// VTRE holds the vertex trees of the group's progressive mesh (VSPL), which
// mode vtrees' server and client walk: their structure, fans included, must
// be that of the trees built from it.
void check_vtre_of_pm(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "vertex trees";
  const Section* base = decoded.find(kBaseTag, group);
  const Section* vspl = decoded.find(kVsplTag, group);
  const Section* vtre = decoded.find(kVtreTag, group);
  Result<ProgressiveMesh> decoded_pm =
      decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
  if (!decoded_pm.is_ok()) return f->add(kVsplTag, who, decoded_pm.status().message());
  Result<VertexTrees> stored = decode_vtre(vtre->data, vtre->size);
  if (!stored.is_ok()) return f->add(kVtreTag, who, stored.status().message());
  Result<VertexTrees> built = build_vertex_trees(decoded_pm.value());
  if (!built.is_ok()) return f->add(kVsplTag, who, built.status().message());
  // Positions are left out: lodbake-pack may quantize VSPL's and BASE's
  // positions and not the hierarchy's, which mode vtrees compares VTRE's
  // with (VtreesDatabase::create() above).
  const VertexTrees& a = stored.value();
  const VertexTrees& b = built.value();
  std::string what;
  if (a.base_vertex_count != b.base_vertex_count || a.parent_vertex != b.parent_vertex)
    what = "its parent vertices are";
  else if (a.vertex_states != b.vertex_states)
    what = "its vertex states are";
  else if (a.run_offsets != b.run_offsets || a.run_closed != b.run_closed ||
           a.vertex_offsets != b.vertex_offsets || a.fan_vertices != b.fan_vertices)
    what = "its fans are";
  if (!what.empty()) f->add(kVtreTag, who, what + " not those of VSPL's progressive mesh");
}

// True when `p` is `k` or an ancestor of `k` in `dag` (parents are below
// their node, so the search stops under p). `seen` is scratch, all 0.
bool dag_reaches(const VsplitDag& dag, uint32_t k, uint32_t p, std::vector<uint8_t>* seen,
                 std::vector<uint32_t>* stack) {
  stack->assign(1, k);
  std::vector<uint32_t> marked;
  bool found = false;
  while (!stack->empty() && !found) {
    const uint32_t v = stack->back();
    stack->pop_back();
    for (uint32_t i = dag.parent_offsets[v]; i < dag.parent_offsets[v + 1]; ++i) {
      const uint32_t q = dag.parents[i];
      if (q == p) {
        found = true;
        break;
      }
      if (q < p || (*seen)[q] != 0) continue;
      (*seen)[q] = 1;
      marked.push_back(q);
      stack->push_back(q);
    }
  }
  for (uint32_t q : marked)
    (*seen)[q] = 0;
  return found;
}

// Mode dag: the DAG must hold every dependency of the PM's lineage (else a
// front it allows is no valid mesh); then its fronts split every node and
// collapse every one.
void check_dag(const Container& decoded, uint32_t group, bool with_hierarchy, Findings* f) {
  const char* who = "mode dag";
  Result<DagStructure> loaded = load_dag_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kDageTag, who, loaded.status().message());
  const ProgressiveMesh& pm = *loaded.value().pm;
  const VsplitDag& dag = *loaded.value().dag;
  Result<DagReplay> replay = DagReplay::create(pm, dag);
  if (!replay.is_ok()) return f->add(kDageTag, who, replay.status().message());
  Result<SplitLineage> lineage = build_split_lineage(pm);
  if (!lineage.is_ok()) return f->add(kVsplTag, who, lineage.status().message());
  Result<VsplitDag> needed = reduce_dependencies(lineage.value());
  if (!needed.is_ok()) return f->add(kVsplTag, who, needed.status().message());
  if (!(needed.value() == dag)) {
    std::vector<uint8_t> seen(dag.node_count(), 0);
    std::vector<uint32_t> stack;
    const VsplitDag& n = needed.value();
    for (uint32_t k = 0; k < n.node_count(); ++k) {
      for (uint32_t i = n.parent_offsets[k]; i < n.parent_offsets[k + 1]; ++i) {
        if (!dag_reaches(dag, k, n.parents[i], &seen, &stack)) {
          return f->add(kDageTag, who,
                        "node " + std::to_string(k) + " does not depend on node " +
                            std::to_string(n.parents[i]) + ", whose triangles its split changes");
        }
      }
    }
  }
  Result<DagFronts> created = DagFronts::create(dag);
  if (!created.is_ok()) return f->add(kDageTag, who, created.status().message());
  DagFronts& fronts = created.value();
  auto cut_problems = [&] {
    TriangleMesh mesh;
    mesh.positions.assign(pm.base.vertex_count() + pm.splits.size(), Vec3f{0, 0, 0});
    const std::vector<uint32_t> cut = dag_cut(lineage.value(), fronts);
    std::vector<std::array<uint32_t, 3>> corners;
    for (uint32_t t : cut) {
      mesh.triangles.push_back(lineage.value().triangles[t]);
      if (!loaded.value().lookup) continue;
      std::array<uint32_t, 3>& c = corners.emplace_back();
      for (int k = 0; k < 3; ++k)
        c[k] = loaded.value().lookup->wedge(lineage.value().face_slot[t], mesh.triangles.back()[k]);
    }
    std::vector<std::string> problems = fronts.check_counters();
    for (std::string& p : triangulation_problems(mesh))
      problems.push_back(std::move(p));
    if (loaded.value().lookup) {
      for (std::string& p : corner_wedge_problems(corners, *loaded.value().wedges))
        problems.push_back(std::move(p));
    }
    return problems;
  };
  for (int side = 0; side < 2; ++side) {
    const bool splitting = side == 0;
    // Sweep the front until it is empty; each sweep makes progress in a
    // well-formed DAG (a node of the front is always legal).
    for (;;) {
      std::vector<uint32_t> front = splitting ? fronts.split_front() : fronts.collapse_front();
      if (front.empty()) break;
      std::sort(front.begin(), front.end());
      if (!splitting) std::reverse(front.begin(), front.end());
      for (uint32_t node : front) {
        const Status s = splitting ? fronts.split(node) : fronts.collapse(node);
        if (!s.is_ok()) return f->add(kDageTag, who, s.message());
      }
    }
    const size_t expected = splitting ? dag.node_count() : 0;
    if (fronts.split_count() != expected) {
      return f->add(kDageTag, who,
                    std::string(splitting ? "splitting" : "collapsing") +
                        " every node stops with " + std::to_string(fronts.split_count()) + " of " +
                        std::to_string(dag.node_count()) + " nodes split");
    }
    if (!f->none(kDageTag, who, splitting ? "the finest cut" : "the base cut", cut_problems()))
      return;
  }
  if (!with_hierarchy) return;
  // With the hierarchy, mode vhier's and mode dag's --validate compare the
  // two: when VSPL is the hierarchy's progressive mesh, their finest meshes
  // must be the same (otherwise the check is not made, nothing refused).
  Result<VhierStructure> h = load_vhier_structure(decoded, group);
  if (!h.is_ok()) return;
  Result<StructureCrossCheck> cross = StructureCrossCheck::create(*h.value().h, pm, dag);
  if (!cross.is_ok()) return;
  const std::vector<uint8_t> all(pm.splits.size(), 1);
  f->none(kDageTag, who, "against VHIE's finest mesh",
          cross.value().compare(all, nullptr, nullptr));
}

// Mode fan: the replay starts at the coarsest mesh (every merge made);
// the runtime also splits everything back to the input.
void check_fan(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "mode fan";
  Result<FanStructure> loaded = load_fan_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kFanhTag, who, loaded.status().message());
  if (!f->none(kFanhTag, who, "the coarsest mesh", loaded.value().replay->check())) return;
  Result<FanRuntime> runtime = FanRuntime::create(loaded.value().input, loaded.value().h);
  if (!runtime.is_ok()) return f->add(kFanhTag, who, runtime.status().message());
  if (!runtime.value().merge_all())
    return f->add(kFanhTag, who, "the coarsest mesh cannot be reached");
  if (!runtime.value().split_all())
    return f->add(kFanhTag, who, "the input mesh cannot be reached back from the coarsest");
  // An asset's fan: every corner of the coarsest front has a wedge of one
  // primitive, and the finest front gives back the input's corners.
  const FanStructure& l = loaded.value();
  if (!l.fronts) return;
  if (!f->none(kWedgTag, who, "the coarsest mesh's corners",
               check_fan_wedges(l.replay->runtime(), *l.fronts, *l.wedges)))
    return;
  Result<std::vector<std::array<uint32_t, 3>>> finest = l.fronts->corners(runtime.value());
  if (!finest.is_ok())
    return f->add(kWedgTag, who, "the input mesh's corners: " + finest.status().message());
  if (finest.value() != l.wedges->base)
    f->add(kWedgTag, who, "the input mesh's corners do not have the input's wedges");
}

// Mode sets: recovery from the full mesh to the coarsest LoD and back, at
// every LoD of a small graph and at kSetsLods spaced ones otherwise.
void check_sets(const Container& decoded, uint32_t group, Findings* f) {
  const char* who = "mode sets";
  Result<SetsStructure> loaded = load_sets_structure(decoded, group);
  if (!loaded.is_ok()) return f->add(kSetsTag, who, loaded.status().message());
  const SetsStructure& s = loaded.value();
  // An asset's strips: run_sets_test() checks every recovered LoD's corners.
  Result<SetsReplay> created =
      SetsReplay::create(*s.pm, *s.graph, s.lookup ? &*s.lookup : nullptr, s.wedges.get());
  if (!created.is_ok()) return f->add(kSetsTag, who, created.status().message());
  const uint32_t lods = created.value().lod_count();
  std::vector<uint32_t> path;
  const uint32_t n = std::min(lods, kSetsLods);
  for (uint32_t i = 0; i < n; ++i) {
    const auto lod =
        n == 1 ? 0u : static_cast<uint32_t>((uint64_t{lods - 1} * i + (n - 1) / 2) / (n - 1));
    if (path.empty() || path.back() != lod) path.push_back(lod);
  }
  for (size_t i = path.size(); i-- > 1;)
    path.push_back(path[i - 1]);
  Result<std::vector<SetsStep>> run = run_sets_test(&created.value(), path, true);
  if (!run.is_ok()) f->add(kSetsTag, who, run.status().message());
}

// --extract of a strips-only container: the strips' triangles over BASE.
void check_strp(const Container& decoded, uint32_t group, Findings* f) {
  const Section* base = decoded.find(kBaseTag, group);
  const Section* strp = decoded.find(kStrpTag, group);
  Result<TriangleMesh> mesh = decode_base(base->data, base->size);
  if (!mesh.is_ok()) return f->add(kBaseTag, "--extract", mesh.status().message());
  Result<TriangleStrips> strips = decode_strp(strp->data, strp->size);
  if (!strips.is_ok()) return f->add(kStrpTag, "--extract", strips.status().message());
  Result<TriangleMesh> out = mesh_from_strips(strips.value(), mesh.value());
  if (!out.is_ok()) return f->add(kStrpTag, "--extract", out.status().message());
  f->none(kStrpTag, "--extract", "the strips' mesh", triangulation_problems(out.value()));
}

}  // namespace

std::vector<SectionFinding> validate_group_structures(const Container& decoded, uint32_t group,
                                                      const std::vector<std::string>& skip) {
  std::vector<SectionFinding> findings;
  Findings f(&findings);
  auto usable = [&](std::initializer_list<const char*> tags) {
    for (const char* tag : tags) {
      if (decoded.find(tag, group) == nullptr) return false;
      if (std::find(skip.begin(), skip.end(), tag) != skip.end()) return false;
    }
    return true;
  };
  try {
    const bool pm = usable({kBaseTag, kVsplTag});
    if (pm) check_pm(decoded, group, &f);
    const bool pm_ok = pm && findings.empty();
    const bool hierarchy = usable({kBaseTag, kVhieTag, kRfinTag});
    if (hierarchy) {
      const size_t before = findings.size();
      check_vhier(decoded, group, &f);
      if (findings.size() == before) check_stream(decoded, group, &f);
      if (findings.size() == before && usable({kVtreTag})) check_vtrees(decoded, group, &f);
    }
    if (pm_ok && usable({kVtreTag})) check_vtre_of_pm(decoded, group, &f);
    if (pm_ok && usable({kDageTag})) check_dag(decoded, group, hierarchy, &f);
    if (usable({kBaseTag, kFanhTag})) check_fan(decoded, group, &f);
    if (pm_ok && usable({kSetsTag})) check_sets(decoded, group, &f);
    if (usable({kBaseTag, kStrpTag})) check_strp(decoded, group, &f);
  } catch (const std::bad_alloc&) {
    findings.push_back({kBaseTag, "out of memory running the deep checks"});
  }
  return findings;
}

std::vector<SectionFinding> validate_container(const Container& decoded) {
  std::vector<SectionFinding> findings;
  const uint32_t groups = std::max<uint32_t>(decoded.group_count(), 1);
  for (uint32_t group = 0; group < groups; ++group) {
    std::vector<SectionFinding> own = validate_group_sections(single_group(decoded, group));
    std::vector<std::string> skip;
    for (const SectionFinding& finding : own)
      skip.push_back(finding.tag);
    for (SectionFinding& finding : validate_group_structures(decoded, group, skip))
      own.push_back(std::move(finding));
    for (SectionFinding& finding : own) {
      if (group != 0) finding.message = "group " + std::to_string(group) + ": " + finding.message;
      findings.push_back(std::move(finding));
    }
  }
  for (SectionFinding& finding : validate_scene_map(decoded))
    findings.push_back(std::move(finding));
  return findings;
}

}  // namespace lodbake
