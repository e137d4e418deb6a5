// The pose filter on the simulator's trajectory (dataset/sim_trajectory.h,
// EuRoC's x-up IMU mounting) with white noise added at 20 Hz, as a VIO
// output would be: it must smooth the positions and, predicting ahead, beat
// holding the last pose. And the heading helpers' defining properties.

#include "navigation/pose_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dataset/sim_trajectory.h"
#include "navigation/kalman_filter.h"

namespace vio {
namespace {

Eigen::Quaterniond RandomRotation(std::mt19937* rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(*rng), n(*rng), n(*rng), n(*rng)).normalized();
}

Eigen::Quaterniond Rz(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

TEST(PoseFilterHeading, YawTurnsWithARotationAboutWorldZ) {
  std::mt19937 rng(5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Quaterniond q = RandomRotation(&rng);
    const double d = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
    EXPECT_NEAR(WrapToPi(YawOf(Rz(d) * q) - YawOf(q) - d), 0.0, 1e-9);
  }
  // A level body: the Z-Y-X yaw.
  EXPECT_NEAR(YawOf(Rz(0.7)), 0.7, 1e-12);
  // EuRoC's x-up IMU (R_v_b of the simulator) heading along +y.
  Eigen::Matrix3d R_v_b;
  R_v_b << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  const Eigen::Quaterniond q_v_b(R_v_b);
  EXPECT_NEAR(WrapToPi(YawOf(Rz(M_PI / 2) * q_v_b) - YawOf(q_v_b)), M_PI / 2,
              1e-12);
}

TEST(PoseFilterHeading, WithYawKeepsTheTilt) {
  std::mt19937 rng(6);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Quaterniond q = RandomRotation(&rng);
    const double yaw = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
    const Eigen::Quaterniond out = WithYaw(q, yaw);
    EXPECT_NEAR(WrapToPi(YawOf(out) - yaw), 0.0, 1e-9);
    // The tilt: where the body's axes point relative to the vertical.
    const Eigen::Vector3d up_in_body_in =
        q.conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_in_body_out =
        out.conjugate() * Eigen::Vector3d::UnitZ();
    EXPECT_LT((up_in_body_in - up_in_body_out).norm(), 1e-9);
  }
}

struct Errors {
  double input = 0, filtered = 0, predicted = 0, held = 0;  // RMSE [m]
  double predicted_yaw = 0, held_yaw = 0;                   // RMSE [rad]
};

// 20 Hz poses of the default simulated flight with N(0, 2 cm) position and
// N(0, 0.01 rad) heading noise, filtered; the prediction `ahead_s` past each
// pose and the pose itself held are compared with the truth at that time.
Errors RunOnSimulatedFlight(double ahead_s) {
  const SimTrajectory truth{SimMotionOptions()};
  PoseFilterOptions options;
  options.position_noise_m = 0.02;
  options.yaw_noise_rad = 0.01;
  options.accel_noise_m_s2 = 1.0;
  options.yaw_accel_noise_rad_s2 = 1.0;
  PoseFilter filter(options);
  std::mt19937 rng(17);
  std::normal_distribution<double> p_noise(0.0, 0.02), yaw_noise(0.0, 0.01);
  Errors sq;
  int n = 0;
  for (int i = 0; i < 800; ++i) {
    const double t = 0.05 * i;
    const SimState s = truth.At(t);
    PoseMeasurement z;
    z.t_ns = static_cast<int64_t>(i) * 50000000;
    z.p_w = s.p_w_b + Eigen::Vector3d(p_noise(rng), p_noise(rng), p_noise(rng));
    z.yaw_rad = YawOf(s.q_w_b) + yaw_noise(rng);
    const FilteredPose f = filter.Add(z);
    if (i < 100) continue;  // past the still start and the filter's start
    const FilteredPose ahead = filter.PredictAhead(ahead_s);
    const SimState later = truth.At(t + ahead_s);
    sq.input += (z.p_w - s.p_w_b).squaredNorm();
    sq.filtered += (f.p_w - s.p_w_b).squaredNorm();
    sq.predicted += (ahead.p_w - later.p_w_b).squaredNorm();
    sq.held += (z.p_w - later.p_w_b).squaredNorm();
    sq.predicted_yaw +=
        std::pow(WrapToPi(ahead.yaw_rad - YawOf(later.q_w_b)), 2);
    sq.held_yaw += std::pow(WrapToPi(z.yaw_rad - YawOf(later.q_w_b)), 2);
    ++n;
  }
  Errors rmse;
  rmse.input = std::sqrt(sq.input / n);
  rmse.filtered = std::sqrt(sq.filtered / n);
  rmse.predicted = std::sqrt(sq.predicted / n);
  rmse.held = std::sqrt(sq.held / n);
  rmse.predicted_yaw = std::sqrt(sq.predicted_yaw / n);
  rmse.held_yaw = std::sqrt(sq.held_yaw / n);
  return rmse;
}

TEST(PoseFilter, SmoothsTheSimulatedFlight) {
  const Errors e = RunOnSimulatedFlight(0.1);
  // Input ~ 2 cm * sqrt(3) = 3.5 cm; filtered about half of it.
  EXPECT_NEAR(e.input, 0.0346, 0.003);
  EXPECT_LT(e.filtered, 0.7 * e.input) << "filtered " << e.filtered;
}

TEST(PoseFilter, PredictionAheadBeatsHoldingTheLastPose) {
  const Errors e = RunOnSimulatedFlight(0.1);
  // About 1 m/s: holding is ~10 cm off after 100 ms.
  EXPECT_GT(e.held, 0.08);
  EXPECT_LT(e.predicted, 0.4 * e.held)
      << "predicted " << e.predicted << " m, held " << e.held << " m";
  EXPECT_LT(e.predicted_yaw, 0.6 * e.held_yaw)
      << "predicted " << e.predicted_yaw << " rad, held " << e.held_yaw;
}

TEST(PoseFilter, RejectsStampsThatDoNotIncrease) {
  PoseFilter filter{PoseFilterOptions()};
  PoseMeasurement z;
  z.t_ns = 100;
  filter.Add(z);
  EXPECT_THROW(filter.Add(z), std::invalid_argument);
  z.t_ns = 200;
  z.yaw_rad = NAN;
  EXPECT_THROW(filter.Add(z), std::invalid_argument);
}

TEST(PoseFilter, OptionsMustBePositive) {
  PoseFilterOptions o;
  o.accel_noise_m_s2 = 0.0;
  try {
    o.Validate();
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("accel_noise_m_s2"),
              std::string::npos);
  }
}

// A heading near +-pi: the filter follows it across the wrap, never through
// zero.
TEST(PoseFilter, FollowsAHeadingAcrossPlusMinusPi) {
  PoseFilter filter{PoseFilterOptions()};
  for (int i = 0; i < 40; ++i) {
    PoseMeasurement z;
    z.t_ns = int64_t{i} * 50000000;
    z.yaw_rad = WrapToPi(M_PI - 0.5 + 0.025 * i);  // crosses pi at i = 20
    const FilteredPose f = filter.Add(z);
    EXPECT_NEAR(WrapToPi(f.yaw_rad - z.yaw_rad), 0.0, 0.05) << "pose " << i;
  }
}

}  // namespace
}  // namespace vio
