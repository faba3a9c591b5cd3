// Quadric: plane distances, area weighting, the minimiser and its refusal
// on singular systems.
#include "lib/simplify/quadric.h"

#include <gtest/gtest.h>

namespace lodbake {
namespace {

TEST(Quadric, PlaneGivesWeightedSquaredDistance) {
  const Quadric q = Quadric::from_plane({0, 0, 1}, -2, 3);  // z = 2, weight 3
  EXPECT_DOUBLE_EQ(q.evaluate({5, -1, 2}), 0);
  EXPECT_DOUBLE_EQ(q.evaluate({0, 0, 5}), 3 * 9);
  EXPECT_DOUBLE_EQ(q.mean_error({0, 0, 5}), 9);
}

TEST(Quadric, TriangleIsAreaWeighted) {
  const Quadric q = Quadric::from_triangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0});
  EXPECT_DOUBLE_EQ(q.weight, 2);
  EXPECT_DOUBLE_EQ(q.evaluate({1, 1, 1}), 2);
  EXPECT_DOUBLE_EQ(q.mean_error({1, 1, 1}), 1);
  const Quadric degenerate = Quadric::from_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  EXPECT_EQ(degenerate.weight, 0);
  EXPECT_EQ(degenerate.mean_error({3, 0, 0}), 0);
}

TEST(Quadric, SumAndScale) {
  Quadric q = Quadric::from_plane({1, 0, 0}, 0, 1) + Quadric::from_plane({0, 1, 0}, -1, 1);
  EXPECT_DOUBLE_EQ(q.evaluate({1, 0, 7}), 1 + 1);
  q *= 2;
  EXPECT_DOUBLE_EQ(q.evaluate({1, 0, 7}), 4);
  EXPECT_DOUBLE_EQ(q.weight, 4);
}

TEST(Quadric, MinimizerOfThreePlanesIsTheirIntersection) {
  const Quadric q = Quadric::from_plane({1, 0, 0}, -1, 1) + Quadric::from_plane({0, 1, 0}, -2, 1) +
                    Quadric::from_plane({0, 0, 1}, 3, 1);
  Vec3d p{};
  ASSERT_TRUE(q.minimizer(&p));
  EXPECT_NEAR(p[0], 1, 1e-12);
  EXPECT_NEAR(p[1], 2, 1e-12);
  EXPECT_NEAR(p[2], -3, 1e-12);
  EXPECT_NEAR(q.evaluate(p), 0, 1e-12);
}

TEST(Quadric, MinimizerRefusesSingularSystems) {
  // Two planes meet in a line: no unique minimiser.
  const Quadric q = Quadric::from_plane({1, 0, 0}, 0, 1) + Quadric::from_plane({0, 1, 0}, 0, 1);
  Vec3d p{7, 7, 7};
  EXPECT_FALSE(q.minimizer(&p));
  EXPECT_EQ(p[0], 7);
  EXPECT_FALSE(Quadric().minimizer(&p));
}

}  // namespace
}  // namespace lodbake
