#include "eval/alignment.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "eval/eval_error.h"
#include "eval/metrics.h"
#include "test/testing/trajectories.h"

namespace vio {
namespace {

using testing::AngleBetween;
using testing::Similarity;
using testing::Transform;

constexpr double kSigma = 0.001;  // [m] position noise of the noisy cases
constexpr int kPoses = 300;

// The ground truth is the Lissajous loop; the estimate lives in its own
// frame: estimate = S^-1(ground truth) + noise, so the alignment must find S.
struct Case {
  Trajectory ground_truth;
  Trajectory estimate;
};

Case MakeCase(const Similarity& S_w_e, double sigma, std::mt19937& rng) {
  Case c;
  c.ground_truth = testing::Lissajous(kPoses);
  c.estimate = testing::AddPositionNoise(
      Transform(S_w_e.Inverse(), c.ground_truth), sigma, rng);
  return c;
}

// Bounds from the noise: n points with spread ~3 m and per-axis noise sigma
// (times the scale, in the ground-truth frame) fix the rotation to about
// sigma / (3 m sqrt(n)) ~ 2e-5 rad and the translation and scale to a few
// sigma / sqrt(n); the bounds below are about 5 times those. The ATE RMSE of
// the residual noise is scale * sigma * sqrt(3 (n - dof) / n) within a few %.
void ExpectRecovered(const Similarity& truth, const Alignment& a, const Case& c,
                     AlignmentMode mode) {
  EXPECT_LT(AngleBetween(a.R_w_e, truth.R_w_e), 1e-4);
  EXPECT_LT((a.t_w_e - truth.t_w_e).norm(), 1e-3 * truth.scale);
  EXPECT_NEAR(a.scale, truth.scale, 1e-4 * truth.scale);
  const AbsoluteTrajectoryError ate =
      ComputeAte(a.Apply(c.estimate), c.ground_truth);
  const double expected = truth.scale * kSigma * std::sqrt(3.0);
  EXPECT_NEAR(ate.translation.rmse, expected, 0.1 * expected)
      << AlignmentModeName(mode);
}

TEST(Alignment, Sim3RecoversAKnownSimilarityFromNoisyPositions) {
  std::mt19937 rng(42);
  const Similarity S{testing::RandomRotation(rng), {3.0, -7.0, 1.5}, 1.7};
  const Case c = MakeCase(S, kSigma, rng);
  ExpectRecovered(S, Align(c.estimate, c.ground_truth, AlignmentMode::kSim3), c,
                  AlignmentMode::kSim3);
}

TEST(Alignment, Se3RecoversAKnownRigidMotionFromNoisyPositions) {
  std::mt19937 rng(43);
  const Similarity S{testing::RandomRotation(rng), {-2.0, 0.5, 4.0}, 1.0};
  const Case c = MakeCase(S, kSigma, rng);
  ExpectRecovered(S, Align(c.estimate, c.ground_truth, AlignmentMode::kSe3), c,
                  AlignmentMode::kSe3);
}

TEST(Alignment, PosYawRecoversAKnownYawAndTranslationFromNoisyPositions) {
  std::mt19937 rng(44);
  const Similarity S{testing::Yaw(2.5), {1.0, 2.0, -0.3}, 1.0};
  const Case c = MakeCase(S, kSigma, rng);
  const Alignment a = Align(c.estimate, c.ground_truth, AlignmentMode::kPosYaw);
  ExpectRecovered(S, a, c, AlignmentMode::kPosYaw);
}

TEST(Alignment, TrajectoryAgainstItselfTransformedHasZeroAte) {
  std::mt19937 rng(5);
  struct Row {
    AlignmentMode mode;
    Similarity S;
  };
  const Row rows[] = {
      {AlignmentMode::kSe3, {testing::RandomRotation(rng), {1, 2, 3}, 1.0}},
      {AlignmentMode::kSim3, {testing::RandomRotation(rng), {-4, 0, 9}, 0.3}},
      {AlignmentMode::kPosYaw, {testing::Yaw(-3.0), {0.5, -8, 2}, 1.0}},
      {AlignmentMode::kNone, {}},
  };
  for (const Row& row : rows) {
    const Case c = MakeCase(row.S, 0.0, rng);
    const Alignment a = Align(c.estimate, c.ground_truth, row.mode);
    const AbsoluteTrajectoryError ate =
        ComputeAte(a.Apply(c.estimate), c.ground_truth);
    EXPECT_LT(ate.translation.max, 1e-9) << AlignmentModeName(row.mode);
    EXPECT_LT(ate.rotation.max, 1e-6) << AlignmentModeName(row.mode);
  }
}

TEST(Alignment, PlanarTrajectoriesAlignWithoutAReflection) {
  // All positions in one plane (a ground robot): the cross-covariance has
  // rank 2 and Umeyama's sign guard must still return a proper rotation.
  std::mt19937 rng(10);
  Trajectory flat = testing::Lissajous(100);
  for (StampedPose& p : flat) p.p_w_b.z() = 0.0;
  for (AlignmentMode mode : {AlignmentMode::kSe3, AlignmentMode::kSim3}) {
    const Similarity S{testing::RandomRotation(rng), {1, -2, 3}, 1.0};
    const Trajectory est = Transform(S.Inverse(), flat);
    const Alignment a = Align(est, flat, mode);
    EXPECT_NEAR(a.R_w_e.determinant(), 1.0, 1e-12) << AlignmentModeName(mode);
    EXPECT_LT(AngleBetween(a.R_w_e, S.R_w_e), 1e-9) << AlignmentModeName(mode);
    EXPECT_LT(ComputeAte(a.Apply(est), flat).translation.max, 1e-9);
  }
}

TEST(Alignment, PosYawRotatesOnlyAboutGravity) {
  // The true transform also rolls and pitches: posyaw must still return a
  // pure rotation about z (it cannot, and must not, undo roll or pitch).
  std::mt19937 rng(6);
  const Similarity S{testing::RandomRotation(rng), {1, 1, 1}, 1.0};
  const Case c = MakeCase(S, 0.0, rng);
  const Alignment a = Align(c.estimate, c.ground_truth, AlignmentMode::kPosYaw);
  EXPECT_NEAR(
      (a.R_w_e * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(),
      0.0, 1e-12);
  EXPECT_NEAR(a.R_w_e.determinant(), 1.0, 1e-12);
}

TEST(Alignment, PosYawIgnoresTheEstimatedOrientations) {
  std::mt19937 rng(7);
  const Case c = MakeCase({testing::Yaw(0.7), {1, 2, 3}, 1.0}, kSigma, rng);
  Trajectory tilted = c.estimate;
  for (StampedPose& p : tilted) {
    p.q_w_b = Eigen::Quaterniond(testing::RandomRotation(rng));
  }
  const Alignment a = Align(c.estimate, c.ground_truth, AlignmentMode::kPosYaw);
  const Alignment b = Align(tilted, c.ground_truth, AlignmentMode::kPosYaw);
  EXPECT_TRUE(a.R_w_e.isApprox(b.R_w_e, 1e-15));
  EXPECT_TRUE(a.t_w_e.isApprox(b.t_w_e, 1e-15));
}

// sum_i |p_w_i - (Rz(yaw) p_e_i + t)|^2 with the optimal t for that yaw.
double PosYawCost(const Case& c, double yaw) {
  const Eigen::Matrix3d R = testing::Yaw(yaw);
  Eigen::Vector3d mean_e = Eigen::Vector3d::Zero(), mean_w = mean_e;
  for (size_t i = 0; i < c.estimate.size(); ++i) {
    mean_e += c.estimate[i].p_w_b / c.estimate.size();
    mean_w += c.ground_truth[i].p_w_b / c.estimate.size();
  }
  const Eigen::Vector3d t = mean_w - R * mean_e;
  double cost = 0.0;
  for (size_t i = 0; i < c.estimate.size(); ++i) {
    cost +=
        (c.ground_truth[i].p_w_b - R * c.estimate[i].p_w_b - t).squaredNorm();
  }
  return cost;
}

TEST(Alignment, PosYawMatchesABruteForceYawSearch) {
  // A transform with roll and pitch and noise: the yaw is then a genuine
  // compromise, found here by scanning yaw on a 1e-4 rad grid and refining.
  std::mt19937 rng(8);
  const Case c =
      MakeCase({testing::RandomRotation(rng), {2, 0, 1}, 1.0}, 0.05, rng);
  double best = 0.0;
  for (double step : {1e-2, 1e-4, 1e-6, 1e-8}) {
    const double centre = best;
    double best_cost = PosYawCost(c, best);
    const double range = step == 1e-2 ? M_PI : 100 * step;
    for (double yaw = centre - range; yaw <= centre + range; yaw += step) {
      const double cost = PosYawCost(c, yaw);
      if (cost < best_cost) {
        best_cost = cost;
        best = yaw;
      }
    }
  }
  const Alignment a = Align(c.estimate, c.ground_truth, AlignmentMode::kPosYaw);
  const double yaw = std::atan2(a.R_w_e(1, 0), a.R_w_e(0, 0));
  EXPECT_NEAR(std::remainder(yaw - best, 2 * M_PI), 0.0, 1e-7);
  EXPECT_LE(PosYawCost(c, yaw), PosYawCost(c, best) * (1 + 1e-12));
}

// A vehicle standing still (EuRoC's first seconds): the positions spread a few
// millimetres, which says nothing about the yaw; the orientations do.
TEST(Alignment, PosYawOfAStaticTrajectoryTakesTheYawFromTheOrientations) {
  std::mt19937 rng(5);
  Trajectory still = testing::Lissajous(100);
  for (auto& pose : still) pose.p_w_b = {1.0, 2.0, 0.5};
  still = testing::AddPositionNoise(still, 0.002, rng);
  const Similarity S_w_e{testing::Yaw(0.7), {3.0, -1.0, 0.2}, 1.0};
  const Trajectory estimate = Transform(S_w_e.Inverse(), still);
  const Alignment a = Align(estimate, still, AlignmentMode::kPosYaw);
  EXPECT_TRUE(a.yaw_from_orientations);
  EXPECT_LT(AngleBetween(a.R_w_e, testing::Yaw(0.7)), 1e-9);
  EXPECT_LT((a.t_w_e - S_w_e.t_w_e).norm(), 1e-9);
  // A moving trajectory still aligns on its positions alone.
  const Trajectory loop = testing::Lissajous(kPoses);
  EXPECT_FALSE(
      Align(Transform(S_w_e.Inverse(), loop), loop, AlignmentMode::kPosYaw)
          .yaw_from_orientations);
}

TEST(Alignment, TooFewOrDegeneratePositionsAreAnEvalError) {
  const Trajectory loop = testing::Lissajous(10);
  const Trajectory two(loop.begin(), loop.begin() + 2);
  EXPECT_THROW(Align(two, two, AlignmentMode::kSe3), EvalError);
  EXPECT_NO_THROW(Align(two, two, AlignmentMode::kPosYaw));
  Trajectory line = loop;
  for (size_t i = 0; i < line.size(); ++i)
    line[i].p_w_b = {1.0 * i, 2.0 * i, 0};
  try {
    Align(line, line, AlignmentMode::kSim3);
    ADD_FAILURE() << "collinear positions accepted";
  } catch (const EvalError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("sim3 alignment is degenerate"));
  }
  EXPECT_THROW(Align(loop, two, AlignmentMode::kSe3), std::invalid_argument);
}

TEST(Alignment, ParsesModeNamesAndRejectsOthers) {
  for (AlignmentMode m : {AlignmentMode::kNone, AlignmentMode::kSe3,
                          AlignmentMode::kSim3, AlignmentMode::kPosYaw}) {
    EXPECT_EQ(ParseAlignmentMode(AlignmentModeName(m)), m);
  }
  EXPECT_THROW(ParseAlignmentMode("sim(3)"), std::invalid_argument);
}

}  // namespace
}  // namespace vio
