// SetGauge and YawBetween (estimator/initial_window.h): the 4-DoF move that
// gives a re-start the running position and yaw.

#include "estimator/initial_window.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimator/static_initializer.h"

namespace vio {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Quaterniond Rot(double angle_rad, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, axis.normalized()));
}

// The body of EuRoC's IMU: x up, z forward (tilted `tilt_rad` off that).
Eigen::Quaterniond XUp(double heading_rad, double tilt_rad) {
  const Eigen::Matrix3d x_up = (Eigen::Matrix3d() << 0, 0, 1,  //
                                0, -1, 0,                      //
                                1, 0, 0)
                                   .finished();
  return Rot(heading_rad, Eigen::Vector3d::UnitZ()) *
         Rot(tilt_rad, Eigen::Vector3d(1, 1, 0)) * Eigen::Quaterniond(x_up);
}

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

TEST(YawBetween, RecoversAPureRotationAboutZForAnyAttitude) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Quaterniond q =
        k == 0 ? XUp(0.3, 0.0)
               : Eigen::Quaterniond(
                     Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)))
                     .normalized();
    const double yaw = u(rng);
    const Eigen::Matrix3d R = q.toRotationMatrix();
    EXPECT_NEAR(
        YawBetween(R,
                   Rot(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R),
        yaw, 1e-12)
        << k;
  }
}

TEST(YawBetween, StaysNearTheYawWhenTheBodyXPointsUp) {
  // A running and a re-started attitude of the same body, 0.4 rad of yaw
  // and 1 deg of tilt apart, body x 2 deg off vertical: the heading of body
  // x (Yaw) is then ill-defined, and its difference was the re-start's yaw
  // (measured 48.6 deg of attitude jump at a stereo re-start).
  const Eigen::Quaterniond q_new = XUp(0.2, 2.0 * kDeg);
  const Eigen::Quaterniond q_run = Rot(0.4, Eigen::Vector3d::UnitZ()) *
                                   Rot(1.0 * kDeg, Eigen::Vector3d::UnitX()) *
                                   q_new;
  const Eigen::Matrix3d R_new = q_new.toRotationMatrix();
  const Eigen::Matrix3d R_run = q_run.toRotationMatrix();
  EXPECT_NEAR(YawBetween(R_new, R_run), 0.4, 1.0 * kDeg);
  // What the difference of headings gives here: far off.
  EXPECT_GT(std::abs(Yaw(R_run) - Yaw(R_new) - 0.4), 10.0 * kDeg);
}

InitialWindow ThreeFrames(const Eigen::Quaterniond& q_newest) {
  InitialWindow w;
  for (int k = 0; k < 3; ++k) {
    InitialFrame f;
    f.p_w_b = Eigen::Vector3d(1.0 * k, 0.5 * k * k, 0.1 * k);
    f.q_w_b = Rot(0.1 * (k - 2), Eigen::Vector3d(0, 1, 1)) * q_newest;
    f.v_w = Eigen::Vector3d(1.0, 1.0 * k, 0.0);
    f.b_a = Eigen::Vector3d(0.1, 0.2, 0.3);
    w.frames.push_back(f);
  }
  w.points_w[7] = Eigen::Vector3d(4.0, -2.0, 1.5);
  return w;
}

TEST(SetGauge, GivesTheNewestTheRunningPoseAndMovesTheWindowRigidly) {
  const InitialWindow before = ThreeFrames(XUp(0.2, 2.0 * kDeg));
  const Eigen::Vector3d p_run(3.0, -1.0, 0.7);
  const Eigen::Quaterniond q_run = Rot(0.4, Eigen::Vector3d::UnitZ()) *
                                   Rot(1.0 * kDeg, Eigen::Vector3d::UnitX()) *
                                   before.frames.back().q_w_b;
  InitialWindow after = before;
  SetGauge(p_run, q_run, &after);
  const InitialFrame& newest = after.frames.back();
  EXPECT_LT((newest.p_w_b - p_run).norm(), 1e-12);
  // The running attitude up to the 1 deg of tilt SetGauge must not change.
  EXPECT_LT(AngleBetween(newest.q_w_b, q_run), 1.0 * kDeg + 1e-9);
  const Eigen::Quaterniond Rz = Rot(0.4, Eigen::Vector3d::UnitZ());
  for (size_t k = 0; k < 3; ++k) {
    const InitialFrame& a = after.frames[k];
    const InitialFrame& b = before.frames[k];
    // Rotated about z by the yaw, roll and pitch kept: world z seen in the
    // body is unchanged.
    EXPECT_LT(((a.q_w_b.conjugate() * Eigen::Vector3d::UnitZ()) -
               (b.q_w_b.conjugate() * Eigen::Vector3d::UnitZ()))
                  .norm(),
              1e-12);
    EXPECT_LT((a.p_w_b - (Rz * (b.p_w_b - before.frames.back().p_w_b) + p_run))
                  .norm(),
              0.02);
    EXPECT_LT((a.v_w - Rz * b.v_w).norm(), 0.02 * b.v_w.norm() + 1e-12);
    EXPECT_EQ(a.b_a, b.b_a);
  }
  // Distances within the window are kept (rigid, no scale).
  EXPECT_NEAR((after.frames[0].p_w_b - after.points_w.at(7)).norm(),
              (before.frames[0].p_w_b - before.points_w.at(7)).norm(), 1e-12);
  EXPECT_NEAR((after.frames[0].p_w_b - newest.p_w_b).norm(),
              (before.frames[0].p_w_b - before.frames[2].p_w_b).norm(), 1e-12);
}

TEST(SetGauge, TheYawFormSetsTheHeadingOfBodyX) {
  InitialWindow w = ThreeFrames(Rot(0.3, Eigen::Vector3d(0.1, 0.2, 1.0)));
  SetGauge(Eigen::Vector3d::Zero(), 0.25, &w);
  EXPECT_NEAR(Yaw(w.frames.back().q_w_b.toRotationMatrix()), 0.25, 1e-12);
  EXPECT_LT(w.frames.back().p_w_b.norm(), 1e-12);
}

}  // namespace
}  // namespace vio
