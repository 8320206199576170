// SE(2) rigid motion: rotation by yaw about the origin, then translation (ROS conventions:
// x forward, y left, yaw counter-clockwise). T_a_b is the pose of frame b in frame a, so it maps
// points given in b into a: p_a = T_a_b * p_b, and T_a_c = T_a_b * T_b_c.
#pragma once

#include <Eigen/Core>

namespace fleetmerge {

// Wraps an angle into (-pi, pi].
double WrapAngle(double angle_rad);

class Pose2 {
 public:
  Pose2() = default;
  Pose2(double x_m, double y_m, double yaw_rad);
  Pose2(const Eigen::Vector2d& translation_m, double yaw_rad);

  double x_m() const { return translation_m_.x(); }
  double y_m() const { return translation_m_.y(); }
  double yaw_rad() const { return yaw_rad_; }
  const Eigen::Vector2d& translation_m() const { return translation_m_; }
  Eigen::Matrix2d rotation() const;

  Pose2 inverse() const;
  Pose2 operator*(const Pose2& T_b_c) const;
  Eigen::Vector2d operator*(const Eigen::Vector2d& p_b) const;

 private:
  Eigen::Vector2d translation_m_ = Eigen::Vector2d::Zero();
  double yaw_rad_ = 0.0;  // always wrapped into (-pi, pi]
};

}  // namespace fleetmerge
