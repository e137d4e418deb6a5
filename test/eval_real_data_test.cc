// The readers and the evaluation on real EuRoC ground truth (MH_05_difficult,
// 111 s at 200 Hz, ~ 130 m of flight): the ground truth subsampled to 20 Hz,
// moved into another frame and written as TUM plays the estimate.

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "dataset/trajectory_io.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "test/testing/trajectories.h"

namespace vio {
namespace {

const std::string& GroundTruthPath() {
  static const std::string path = std::string(VIO_SHARED_DIR) +
                                  "/data/euroc_MH_05_imu_gt/mav0/"
                                  "state_groundtruth_estimate0/data.csv";
  return path;
}

const Trajectory& GroundTruth() {
  static const Trajectory gt = ReadTrajectory(GroundTruthPath());
  return gt;
}

// Every 10th pose, 2 ms late (the nearest 200 Hz stamp is still its own),
// moved by S^-1, with optional noise, written as TUM and read back.
Trajectory MakeEstimate(const testing::Similarity& S_w_e, double sigma_m,
                        const std::string& name) {
  std::mt19937 rng(11);
  Trajectory est;
  for (size_t i = 0; i < GroundTruth().size(); i += 10) {
    StampedPose p = S_w_e.Inverse().Apply(GroundTruth()[i]);
    p.t_ns += 2000000;
    est.push_back(p);
  }
  est = testing::AddPositionNoise(est, sigma_m, rng);
  const std::string path = ::testing::TempDir() + "real_data_" + name + ".txt";
  WriteTum(path, est);
  return ReadTrajectory(path);
}

TEST(EvalRealData, SubsampledGroundTruthAssociatesWithItsOwnStamps) {
  const Trajectory est = MakeEstimate({}, 0.0, "identity");
  ASSERT_EQ(GroundTruth().size(), 22212u);
  ASSERT_EQ(est.size(), 2222u);
  const Association a = Associate(est, GroundTruth());
  ASSERT_EQ(a.size(), est.size());
  EXPECT_TRUE(a.walked_estimate);
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.ground_truth[k].t_ns, GroundTruth()[10 * k].t_ns) << k;
  }
  // 2 ms late is not within 1 ms: nothing associates.
  EXPECT_EQ(Associate(est, GroundTruth(), {0.001}).size(), 0u);
}

TEST(EvalRealData, EachAlignmentUndoesItsTransformToTheTumPrecision) {
  std::mt19937 rng(12);
  struct Row {
    AlignmentMode mode;
    testing::Similarity S;
  };
  const Row rows[] = {
      {AlignmentMode::kSe3, {testing::RandomRotation(rng), {10, -3, 2}, 1.0}},
      {AlignmentMode::kSim3, {testing::RandomRotation(rng), {-5, 8, 1}, 2.5}},
      {AlignmentMode::kPosYaw, {testing::Yaw(1.2), {3, 4, -1}, 1.0}},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(AlignmentModeName(row.mode));
    const Trajectory est =
        MakeEstimate(row.S, 0.0, AlignmentModeName(row.mode));
    const Association assoc = Associate(est, GroundTruth());
    const Alignment a = Align(assoc.estimate, assoc.ground_truth, row.mode);
    EXPECT_LT(testing::AngleBetween(a.R_w_e, row.S.R_w_e), 1e-7);
    EXPECT_LT((a.t_w_e - row.S.t_w_e).norm(), 1e-6);
    EXPECT_NEAR(a.scale, row.S.scale, 1e-7);
    // The TUM file keeps 9 significant digits: ~1e-8 m on positions of ~10 m.
    const AbsoluteTrajectoryError ate =
        ComputeAte(a.Apply(assoc.estimate), assoc.ground_truth);
    EXPECT_LT(ate.translation.max, 1e-6);
    EXPECT_LT(ate.rotation.max, 1e-5);
  }
}

TEST(EvalRealData, NoisyEstimateGivesTheNoiseAsAteAndSomeRpe) {
  const double sigma = 0.01;  // [m] per axis
  const testing::Similarity S{testing::Yaw(-0.4), {1, 2, 3}, 1.0};
  const Trajectory est = MakeEstimate(S, sigma, "noisy");
  const Association assoc = Associate(est, GroundTruth());
  const Alignment a =
      Align(assoc.estimate, assoc.ground_truth, AlignmentMode::kSe3);
  const Trajectory aligned = a.Apply(assoc.estimate);
  const AbsoluteTrajectoryError ate = ComputeAte(aligned, assoc.ground_truth);
  // rmse of 3-D Gaussian noise: sigma sqrt(3); 2222 poses -> ~1.5 % spread.
  EXPECT_NEAR(ate.translation.rmse, sigma * std::sqrt(3.0),
              0.05 * sigma * std::sqrt(3.0));
  for (double delta : {1.0, 2.0, 5.0, 10.0}) {
    const RelativePoseError rpe =
        ComputeRpe(aligned, assoc.ground_truth, delta, RpeUnit::kMeters);
    EXPECT_GT(rpe.pairs.size(), 5u) << delta;
    // Difference of two noisy positions: ~ sigma sqrt(6) per pair.
    EXPECT_NEAR(rpe.translation.rmse, sigma * std::sqrt(6.0),
                0.5 * sigma * std::sqrt(6.0))
        << delta;
  }
}

}  // namespace
}  // namespace vio
