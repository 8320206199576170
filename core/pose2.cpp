#include "core/pose2.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace fleetmerge {

double WrapAngle(double angle_rad) {
  // remainder(x, 2 pi) is x itself for |x| <= pi (x / 2 pi rounds to 0, a tie to even): the
  // common case skips the library call, with the same result (a fleet's triangle votes wrap
  // ~10^7 angles).
  double wrapped =
      std::abs(angle_rad) <= M_PI ? angle_rad : std::remainder(angle_rad, 2.0 * M_PI);  // [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

Pose2::Pose2(double x_m, double y_m, double yaw_rad)
    : translation_m_(x_m, y_m), yaw_rad_(WrapAngle(yaw_rad)) {}

Pose2::Pose2(const Eigen::Vector2d& translation_m, double yaw_rad)
    : translation_m_(translation_m), yaw_rad_(WrapAngle(yaw_rad)) {}

Eigen::Matrix2d Pose2::rotation() const { return Eigen::Rotation2Dd(yaw_rad_).toRotationMatrix(); }

Pose2 Pose2::inverse() const {
  const Eigen::Matrix2d R_inv = rotation().transpose();
  return Pose2(-(R_inv * translation_m_), -yaw_rad_);
}

Pose2 Pose2::operator*(const Pose2& T_b_c) const {
  return Pose2(translation_m_ + rotation() * T_b_c.translation_m_, yaw_rad_ + T_b_c.yaw_rad_);
}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& p_b) const {
  return translation_m_ + rotation() * p_b;
}

}  // namespace fleetmerge
