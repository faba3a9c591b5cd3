// Mode fan of the replay runtime (lib/replay/fan_replay.h): on the fandisk
// and the camel head (boundary), both built-in paths keep a valid mesh every
// frame, refine when close and coarsen what leaves the view; a vanishing
// tolerance with the whole model in view reaches the input exactly, a view
// away from the model the coarsest mesh; the coarse and the fine path end in
// the same mesh; replays are deterministic.
#include "lib/replay/fan_replay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>

#include "lib/fanmerge/fan_build.h"
#include "tests/unit/simplify_test_meshes.h"

namespace lodbake {
namespace {

struct Built {
  const char* name = "";
  TriangleMesh input;
  FanBuildResult fan;
};

Built build(const char* name, const char* file) {
  Built b;
  b.name = name;
  b.input = load_clean_mesh(file);
  Result<FanBuildResult> r = build_fan_hierarchy(b.input, FanBuildOptions());
  EXPECT_TRUE(r.is_ok()) << r.status().message();
  if (r.is_ok()) b.fan = std::move(r).value();
  return b;
}

const std::vector<Built>& meshes() {
  static const std::vector<Built> built = [] {
    std::vector<Built> v;
    v.push_back(build("fandisk", "cgal_fandisk.off"));
    v.push_back(build("camelhead (boundary)", "igl_camelhead.off"));
    return v;
  }();
  return built;
}

FanReplay make_replay(const Built& b, FanReplay::Start start = FanReplay::Start::kCoarsest) {
  Result<FanReplay> r = FanReplay::create(b.input, b.fan.hierarchy, start);
  EXPECT_TRUE(r.is_ok()) << r.status().message();
  return std::move(r).value();
}

std::multiset<std::array<uint32_t, 3>> triangle_set(const TriangleMesh& mesh) {
  std::multiset<std::array<uint32_t, 3>> out;
  for (const Triangle& t : mesh.triangles) {
    // Rotate the smallest index first: the same oriented triangle compares equal.
    const size_t m = static_cast<size_t>(std::min_element(t.begin(), t.end()) - t.begin());
    out.insert({t[m], t[(m + 1) % 3], t[(m + 2) % 3]});
  }
  return out;
}

struct Totals {
  size_t fan_merges = 0, fan_splits = 0, collapses = 0, splits = 0;
  size_t coarsening_after_approach = 0, max_triangles = 0, frames = 0;
  std::vector<size_t> per_frame;  // triangles, then the operation counts
};

Totals replay(FanReplay* replay, const BoundingSphere& sphere, const std::vector<CameraFrame>& path,
              const FanReplayOptions& options, bool validate = true) {
  Totals t;
  for (size_t i = 0; i < path.size(); ++i) {
    Result<FanFrameStats> r = replay->adapt(sphere, path[i], options);
    EXPECT_TRUE(r.is_ok()) << "frame " << i << ": " << r.status().message();
    if (!r.is_ok()) return t;
    const FanFrameStats& f = r.value();
    if (validate) {
      const std::vector<std::string> problems = replay->check();
      EXPECT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();
      if (!problems.empty()) return t;
    }
    EXPECT_EQ(f.triangles, replay->runtime().triangle_count());
    EXPECT_EQ(f.active, replay->runtime().active().size());
    t.fan_merges += f.fan_merges;
    t.fan_splits += f.fan_splits;
    t.collapses += f.collapses;
    t.splits += f.splits;
    if (i >= 30) t.coarsening_after_approach += f.fan_merges + f.collapses;
    t.max_triangles = std::max(t.max_triangles, f.triangles);
    t.per_frame.insert(t.per_frame.end(),
                       {f.triangles, f.active, f.fan_merges, f.fan_splits, f.collapses, f.splits});
    ++t.frames;
  }
  return t;
}

// Adapts to one camera until a frame changes nothing (at most `limit` frames).
size_t settle(FanReplay* replay, const BoundingSphere& sphere, const CameraFrame& frame,
              const FanReplayOptions& options, size_t limit = 100) {
  for (size_t i = 0; i < limit; ++i) {
    Result<FanFrameStats> r = replay->adapt(sphere, frame, options);
    EXPECT_TRUE(r.is_ok());
    if (!r.is_ok() || r.value().operations() == 0) return i;
  }
  return limit;
}

CameraFrame whole_model_in_view(const BoundingSphere& s) {
  CameraFrame f;
  f.eye = {s.center[0], s.center[1], s.center[2] + 4 * s.radius};
  f.target = s.center;
  return f;
}

TEST(FanReplay, StartsAtTheCoarsestMeshOrTheInput) {
  for (const Built& b : meshes()) {
    SCOPED_TRACE(b.name);
    FanReplay coarse = make_replay(b);
    EXPECT_EQ(coarse.runtime().mesh().triangles, b.fan.coarsest.triangles);
    EXPECT_TRUE(coarse.check().empty());
    FanReplay full = make_replay(b, FanReplay::Start::kInput);
    EXPECT_EQ(full.runtime().mesh().triangles, b.input.triangles);
    EXPECT_TRUE(full.check().empty());
  }
}

TEST(FanReplay, ViewDataCoverTheSubtree) {
  const Built& b = meshes()[0];
  FanReplay r = make_replay(b);
  const FanRuntime& rt = r.runtime();
  for (uint32_t node = rt.leaf_count(); node < rt.node_count(); ++node) {
    EXPECT_GE(r.saturated_error(node), rt.error(node));
    for (uint32_t i = 0; i <= rt.collapsible_children(node); ++i) {
      const uint32_t c = rt.child(node, i);
      EXPECT_GE(r.saturated_error(node), r.saturated_error(c));
      EXPECT_GE(r.radius(node) * 1.0001f + 1e-6f, r.radius(c));
    }
  }
}

TEST(FanReplay, ScanAndOrbitKeepAValidMeshAndAdapt) {
  for (const Built& b : meshes()) {
    SCOPED_TRACE(b.name);
    const BoundingSphere sphere = bounding_sphere(b.input.positions);
    for (const std::vector<CameraFrame>& path : {scan_path(sphere, 60), orbit_path(sphere, 60)}) {
      FanReplay r = make_replay(b);
      const Totals t = replay(&r, sphere, path, FanReplayOptions());
      EXPECT_EQ(t.frames, path.size());
      // Close to the model it refines, on both paths...
      EXPECT_GT(t.fan_splits + t.splits, 0u);
      EXPECT_GT(t.max_triangles, b.fan.coarsest.triangle_count());
      EXPECT_LE(t.max_triangles, b.input.triangle_count());
      // ... and what leaves the view is coarsened again.
      EXPECT_GT(t.coarsening_after_approach, 0u);
      // Both paths are used.
      EXPECT_GT(t.fan_merges + t.fan_splits, 0u);
      EXPECT_GT(t.collapses + t.splits, 0u);
    }
  }
}

TEST(FanReplay, VanishingToleranceReachesTheInputExactly) {
  for (const Built& b : meshes()) {
    SCOPED_TRACE(b.name);
    const BoundingSphere sphere = bounding_sphere(b.input.positions);
    FanReplayOptions options;
    options.tolerance_pixels = 0;
    for (float fraction : {0.0f, 0.5f, 2.0f}) {
      options.coarse_fraction = fraction;
      FanReplay r = make_replay(b);
      EXPECT_LT(settle(&r, sphere, whole_model_in_view(sphere), options), 100u);
      EXPECT_EQ(r.runtime().mesh().triangles, b.input.triangles) << fraction;
      EXPECT_TRUE(r.check().empty());
    }
  }
}

// Every target is "all merged": with the construction dependencies, the
// runtime merges its way to exactly the coarsest mesh, in scan order rather
// than construction order; without them it gets stuck above it.
TEST(FanReplay, LookingAwayReachesTheCoarsestMesh) {
  for (const Built& b : meshes()) {
    SCOPED_TRACE(b.name);
    const BoundingSphere sphere = bounding_sphere(b.input.positions);
    CameraFrame away = whole_model_in_view(sphere);
    away.target = {away.eye[0], away.eye[1], away.eye[2] + 1};  // the model is behind the eye
    {
      Result<FanReplay> loose =
          FanReplay::create(b.input, b.fan.hierarchy, FanReplay::Start::kInput, false);
      ASSERT_TRUE(loose.is_ok());
      settle(&loose.value(), sphere, away, FanReplayOptions());
      EXPECT_TRUE(loose.value().check().empty());
      EXPECT_GT(loose.value().runtime().triangle_count(), b.fan.coarsest.triangle_count());
    }
    FanReplay r = make_replay(b, FanReplay::Start::kInput);
    r.adapt(sphere, away, FanReplayOptions());
    for (uint32_t node = r.runtime().leaf_count(); node < r.runtime().node_count(); ++node)
      ASSERT_EQ(r.target(node), r.runtime().collapsible_children(node));
    EXPECT_LT(settle(&r, sphere, away, FanReplayOptions()), 100u);
    EXPECT_EQ(triangle_set(r.runtime().mesh()), triangle_set(b.fan.coarsest));
    EXPECT_TRUE(r.check().empty());
  }
}

// The same static view reached with only fan-merges / fan-splits towards the
// ends of the fine paths and with single steps only: the same mesh.
TEST(FanReplay, CoarseAndFinePathsAgree) {
  for (const Built& b : meshes()) {
    SCOPED_TRACE(b.name);
    const BoundingSphere sphere = bounding_sphere(b.input.positions);
    // Close, looking at the model's lower part: some fans split, some merged.
    const CameraFrame view = scan_path(sphere, 60)[60];
    FanReplayOptions coarse, fine;
    coarse.coarse_fraction = 0;
    fine.coarse_fraction = 2;
    FanReplay a = make_replay(b), c = make_replay(b);
    size_t fan_ops = 0, fine_ops = 0, a_fine = 0;
    for (int i = 0; i < 100; ++i) {
      const FanFrameStats sa = a.adapt(sphere, view, coarse).value();
      const FanFrameStats sc = c.adapt(sphere, view, fine).value();
      fan_ops += sa.fan_merges + sa.fan_splits;
      a_fine += sa.collapses + sa.splits;
      fine_ops += sc.collapses + sc.splits;
      EXPECT_EQ(sc.fan_merges + sc.fan_splits, 0u);
      if (sa.operations() == 0 && sc.operations() == 0) break;
    }
    EXPECT_GT(fan_ops, 0u);
    EXPECT_GT(fine_ops, a_fine);
    EXPECT_TRUE(a.check().empty());
    EXPECT_TRUE(c.check().empty());
    EXPECT_GT(a.runtime().triangle_count(), b.fan.coarsest.triangle_count());
    EXPECT_LT(a.runtime().triangle_count(), b.input.triangle_count());
    EXPECT_EQ(triangle_set(a.runtime().mesh()), triangle_set(c.runtime().mesh()));
  }
}

TEST(FanReplay, TargetsFollowDistanceAndTolerance) {
  const Built& b = meshes()[0];
  const BoundingSphere sphere = bounding_sphere(b.input.positions);
  FanReplay r = make_replay(b);
  CameraFrame near_view = whole_model_in_view(sphere), far_view = near_view;
  far_view.eye[2] = sphere.center[2] + 40 * sphere.radius;
  size_t near_sum = 0, far_sum = 0, coarse_sum = 0;
  auto sum = [&](const CameraFrame& f, float tolerance) {
    FanReplayOptions o;
    o.tolerance_pixels = tolerance;
    r.adapt(sphere, f, o);
    size_t s = 0;
    for (uint32_t node = r.runtime().leaf_count(); node < r.runtime().node_count(); ++node) {
      EXPECT_LE(r.target(node), r.runtime().collapsible_children(node));
      s += r.target(node);
    }
    return s;
  };
  near_sum = sum(near_view, 1);
  far_sum = sum(far_view, 1);
  coarse_sum = sum(near_view, 8);
  EXPECT_LT(near_sum, far_sum);
  EXPECT_LT(near_sum, coarse_sum);
}

TEST(FanReplay, Deterministic) {
  const Built& b = meshes()[1];
  const BoundingSphere sphere = bounding_sphere(b.input.positions);
  const std::vector<CameraFrame> path = orbit_path(sphere, 60);
  FanReplay x = make_replay(b), y = make_replay(b);
  const Totals tx = replay(&x, sphere, path, FanReplayOptions(), false);
  const Totals ty = replay(&y, sphere, path, FanReplayOptions(), false);
  EXPECT_EQ(tx.per_frame, ty.per_frame);
  EXPECT_EQ(x.runtime().mesh().triangles, y.runtime().mesh().triangles);
  EXPECT_EQ(x.runtime().active().nodes(), y.runtime().active().nodes());
}

// A FANH whose lists were damaged (the first and the last removed triangles
// swapped) still passes the structural checks; the merges then cannot all
// be made:
// invalid input, not a runtime failure, with or without the construction's
// replay at start-up.
TEST(FanReplay, DamagedListsAreInvalidInput) {
  const Built& b = meshes()[0];
  FanHierarchy damaged = b.fan.hierarchy;
  ASSERT_FALSE(damaged.removed.empty());
  std::swap(damaged.removed.front(), damaged.removed.back());
  Result<FanReplay> r = FanReplay::create(b.input, damaged, FanReplay::Start::kCoarsest, false);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput) << r.status().message();
  EXPECT_EQ(r.status().message(), "the fan hierarchy's coarsest mesh cannot be reached");
  r = FanReplay::create(b.input, damaged, FanReplay::Start::kCoarsest, true);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput) << r.status().message();
}

TEST(FanReplay, RejectsAHierarchyOfAnotherMesh) {
  Result<FanReplay> r = FanReplay::create(meshes()[0].input, meshes()[1].fan.hierarchy);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

}  // namespace
}  // namespace lodbake
