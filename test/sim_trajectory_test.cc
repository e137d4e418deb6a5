#include "dataset/sim_trajectory.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "geometry/so3.h"

namespace vio {
namespace {

constexpr double kStep = 1e-5;  // central-difference step [s]

// Central differences of position, velocity and attitude at `t`.
struct Numeric {
  Eigen::Vector3d v, a, w_b;
};

Numeric Differentiate(const SimTrajectory& trajectory, double t) {
  const SimState before = trajectory.At(t - kStep);
  const SimState after = trajectory.At(t + kStep);
  Numeric n;
  n.v = (after.p_w_b - before.p_w_b) / (2.0 * kStep);
  n.a = (after.v_w - before.v_w) / (2.0 * kStep);
  // R(t + h) = R(t - h) Exp(w_b 2h) to first order, w_b in the body frame.
  n.w_b = Log(before.q_w_b.conjugate() * after.q_w_b) / (2.0 * kStep);
  return n;
}

TEST(SimTrajectory, AnalyticDerivativesMatchCentralDifferences) {
  const SimTrajectory trajectory{SimMotionOptions()};
  // Through the still segment, the blend and the steady motion (not on the
  // segment boundaries, where s'' has a kink and differences are one-sided).
  for (double t = 0.37; t < 40.0; t += 0.5) {
    SCOPED_TRACE(t);
    const SimState state = trajectory.At(t);
    const Numeric numeric = Differentiate(trajectory, t);
    EXPECT_LT((state.v_w - numeric.v).norm(), 1e-8);
    EXPECT_LT((state.a_w - numeric.a).norm(), 1e-6);
    EXPECT_LT((state.w_b - numeric.w_b).norm(), 1e-8);
  }
}

TEST(SimTrajectory, StillStartBlendsContinuouslyIntoTheMotion) {
  const SimMotionOptions options;
  const SimTrajectory trajectory(options);
  const SimState rest = trajectory.At(0.5);
  EXPECT_EQ(rest.v_w, Eigen::Vector3d::Zero());
  EXPECT_EQ(rest.a_w, Eigen::Vector3d::Zero());
  EXPECT_EQ(rest.w_b, Eigen::Vector3d::Zero());
  // The body is mounted like EuRoC's IMU: x up, so at rest the specific force
  // R^T (a - g) is (+9.81, 0, 0).
  const Eigen::Vector3d f_b =
      rest.q_w_b.conjugate() * Eigen::Vector3d(0.0, 0.0, 9.81);
  EXPECT_LT((f_b - Eigen::Vector3d(9.81, 0.0, 0.0)).norm(), 1e-12);
  // Velocity and acceleration have no jump at either end of the blend.
  for (double t_edge : {options.still_duration_s,
                        options.still_duration_s + options.blend_duration_s}) {
    const SimState a = trajectory.At(t_edge - 1e-7);
    const SimState b = trajectory.At(t_edge + 1e-7);
    EXPECT_LT((a.v_w - b.v_w).norm(), 1e-6) << t_edge;
    EXPECT_LT((a.a_w - b.a_w).norm(), 1e-5) << t_edge;
    EXPECT_LT((a.w_b - b.w_b).norm(), 1e-6) << t_edge;
  }
}

TEST(SimTrajectory, DefaultMotionIsLikeAHandHeldOrDroneSequence) {
  const SimTrajectory trajectory{SimMotionOptions()};
  double max_speed = 0.0, max_rate = 0.0, max_acc = 0.0;
  double min_speed = 1e9;
  for (double t = 4.0; t < 40.0; t += 0.01) {
    const SimState s = trajectory.At(t);
    max_speed = std::max(max_speed, s.v_w.norm());
    min_speed = std::min(min_speed, s.v_w.norm());
    max_rate = std::max(max_rate, s.w_b.norm());
    max_acc = std::max(max_acc, s.a_w.norm());
  }
  EXPECT_GT(min_speed, 0.5);  // always moving once the blend is over
  EXPECT_LT(max_speed, 1.6);  // about 1 m/s
  EXPECT_GT(max_rate, 0.3);   // every axis excited, yet gentle
  EXPECT_LT(max_rate, 1.0);
  EXPECT_GT(max_acc, 0.3);
  EXPECT_LT(max_acc, 2.0);
}

// A start in motion: no still segment, no blend, tau begins at the phase.
SimMotionOptions InMotion(SimShape shape, double phase_s) {
  SimMotionOptions o;
  o.shape = shape;
  o.still_duration_s = 0.0;
  o.blend_duration_s = 0.0;
  o.start_phase_s = phase_s;
  return o;
}

TEST(SimTrajectory, EveryShapeHasConsistentDerivatives) {
  for (SimShape shape : {SimShape::kEllipse, SimShape::kRotation,
                         SimShape::kLine, SimShape::kCircle}) {
    SimMotionOptions o = InMotion(shape, 1.3);
    o.attitude_rate_factor = 2.5;
    const SimTrajectory trajectory(o);
    for (double t = 0.21; t < 12.0; t += 0.7) {
      SCOPED_TRACE(std::string(SimShapeName(shape)) + " t " +
                   std::to_string(t));
      const SimState state = trajectory.At(t);
      const Numeric numeric = Differentiate(trajectory, t);
      EXPECT_LT((state.v_w - numeric.v).norm(), 1e-8);
      EXPECT_LT((state.a_w - numeric.a).norm(), 1e-6);
      EXPECT_LT((state.w_b - numeric.w_b).norm(), 1e-7);
    }
  }
}

TEST(SimTrajectory, StartPhaseStartsInMotionWhereTheLapIs) {
  const SimTrajectory from_zero(InMotion(SimShape::kEllipse, 0.0));
  const SimTrajectory from_phase(InMotion(SimShape::kEllipse, 4.0));
  const SimState a = from_zero.At(4.0);
  const SimState b = from_phase.At(0.0);
  EXPECT_LT((a.p_w_b - b.p_w_b).norm(), 1e-12);
  EXPECT_LT((a.v_w - b.v_w).norm(), 1e-12);
  EXPECT_GT(b.v_w.norm(), 0.5);  // moving from the first instant
  EXPECT_LT(a.q_w_b.angularDistance(b.q_w_b), 1e-12);
}

TEST(SimTrajectory, DegenerateShapesHaveNoExcitationWhereTheyShouldNot) {
  const Eigen::Vector3d g_w(0.0, 0.0, -9.81);
  // Pure rotation: the IMU stays where it is, the attitude keeps turning.
  const SimTrajectory rotation(InMotion(SimShape::kRotation, 2.0));
  double max_rate = 0.0;
  for (double t = 0.0; t < 10.0; t += 0.1) {
    const SimState s = rotation.At(t);
    EXPECT_LT((s.p_w_b - rotation.At(0.0).p_w_b).norm(), 1e-12);
    EXPECT_EQ(s.v_w, Eigen::Vector3d::Zero());
    max_rate = std::max(max_rate, s.w_b.norm());
  }
  EXPECT_GT(max_rate, 0.3);
  // Constant velocity, constant attitude: the IMU reads gravity only.
  const SimTrajectory line(InMotion(SimShape::kLine, 0.0));
  for (double t = 0.0; t < 10.0; t += 0.1) {
    const SimState s = line.At(t);
    EXPECT_LT((s.v_w - line.At(0.0).v_w).norm(), 1e-12);
    EXPECT_EQ(s.a_w, Eigen::Vector3d::Zero());
    EXPECT_EQ(s.w_b, Eigen::Vector3d::Zero());
  }
  EXPECT_NEAR(line.At(0.0).v_w.norm(), 0.4, 1e-12);  // 2 * 3 m / 15 s
  // Constant-speed turn with the heading along the path: the specific force
  // R^T (a - g) is the same vector in the body frame all along.
  const SimTrajectory circle(InMotion(SimShape::kCircle, 0.0));
  const SimState c0 = circle.At(0.0);
  const Eigen::Vector3d f0 = c0.q_w_b.conjugate() * (c0.a_w - g_w);
  for (double t = 0.0; t < 10.0; t += 0.1) {
    const SimState s = circle.At(t);
    EXPECT_LT((s.q_w_b.conjugate() * (s.a_w - g_w) - f0).norm(), 1e-9);
    EXPECT_NEAR(s.p_w_b.z(), 1.2, 1e-12);
  }
  EXPECT_GT(c0.a_w.norm(), 0.3);  // yet it does accelerate (centripetal)
}

TEST(SimTrajectory, InvalidOptionsAreRejectedWithTheFieldName) {
  SimMotionOptions options;
  std::string message;
  options.lap_period_s = 0.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "lap_period_s must be > 0 (got 0.000000)");
  options = SimMotionOptions();
  options.blend_duration_s = 0.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message.rfind("blend_duration_s", 0), 0u);
  EXPECT_THROW(SimTrajectory{options}, std::invalid_argument);
}

}  // namespace
}  // namespace vio
