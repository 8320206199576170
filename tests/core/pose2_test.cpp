#include "core/pose2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fleetmerge {
namespace {

TEST(WrapAngle, KeepsHalfOpenIntervalAtPi) {
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(WrapAngle(3.0 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(-M_PI + 1e-9), -M_PI + 1e-9, 1e-15);
  EXPECT_NEAR(WrapAngle(2.0 * M_PI + 0.25), 0.25, 1e-12);
}

TEST(Pose2, ComposeWithInverseIsIdentityAtRandomPoses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-50.0, 50.0), yaw(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 T_a_b(xy(rng), xy(rng), yaw(rng));
    const Pose2 I = T_a_b * T_a_b.inverse();
    EXPECT_NEAR(I.x_m(), 0.0, 1e-9);
    EXPECT_NEAR(I.y_m(), 0.0, 1e-9);
    EXPECT_NEAR(I.yaw_rad(), 0.0, 1e-12);
  }
}

TEST(Pose2, CompositionMatchesPointMapping) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xy(-20.0, 20.0), yaw(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 T_a_b(xy(rng), xy(rng), yaw(rng));
    const Pose2 T_b_c(xy(rng), xy(rng), yaw(rng));
    const Eigen::Vector2d p_c(xy(rng), xy(rng));
    EXPECT_TRUE(((T_a_b * T_b_c) * p_c).isApprox(T_a_b * (T_b_c * p_c), 1e-9));
  }
}

TEST(Pose2, QuarterTurnMovesXAxisToYAxis) {
  const Pose2 T(1.0, 2.0, M_PI / 2);
  const Eigen::Vector2d p = T * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Pose2, TinyRotationsStayAccurate) {
  const Pose2 T(0.0, 0.0, 1e-8);
  EXPECT_NEAR((T * T.inverse()).yaw_rad(), 0.0, 1e-20);
  EXPECT_NEAR((T * Eigen::Vector2d(1.0, 0.0)).y(), 1e-8, 1e-20);
}

}  // namespace
}  // namespace fleetmerge
