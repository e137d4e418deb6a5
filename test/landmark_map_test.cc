// The estimator's mapped landmarks (estimator/landmark_map.h) against the
// simulator's true landmarks: after the posyaw alignment that maps the
// estimated trajectory onto the truth, the well-triangulated landmarks must
// lie where the simulator put the landmarks their tracks followed.

#include "estimator/landmark_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

#include "estimator/sequence_runner.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "testing/sim_replay.h"

namespace vio {
namespace {

TEST(LandmarkMap, MappedLandmarksLieOnTheSimulatedOnes) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, false));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  Estimator estimator(testing::OptionsFor(sim.options), VisualFactorOptions(),
                      sim.options.imu.noise, PreintegrationOptions(),
                      prepared.cameras);
  const std::vector<EstimatorOutput> outputs =
      RunSequence(&estimator, sim.imu, prepared.frames);
  ASSERT_EQ(estimator.summary().resets, 0);

  Trajectory estimate, truth;
  for (const EstimatorOutput& o : outputs) {
    if (o.processed && o.initialized) {
      estimate.push_back({o.t_ns, o.p_w_b, o.q_w_b});
    }
  }
  for (const StampedState& s : sim.ground_truth) truth.push_back(PoseOf(s));
  const Association a = Associate(estimate, truth);
  const Alignment align =
      Align(a.estimate, a.ground_truth, AlignmentMode::kPosYaw);

  const std::map<int64_t, MappedLandmark> mapped = estimator.MappedLandmarks();
  std::vector<std::pair<double, double>> by_angle;
  for (const auto& [feature_id, m] : mapped) {
    const Eigen::Vector3d& p_e = m.p_w;
    ASSERT_LT(feature_id, static_cast<int64_t>(sim.landmark_of_feature.size()));
    const Eigen::Vector3d p_w = align.R_w_e * p_e + align.t_w_e;
    by_angle.push_back(
        {m.parallax_deg,
         (p_w - sim.landmarks_w[sim.landmark_of_feature[feature_id]]).norm()});
  }
  // Far more than a window holds: the marginalised ones are kept.
  const double most_in_window =
      estimator.summary().landmarks_per_step.Quantile(1.0);
  EXPECT_GT(static_cast<double>(mapped.size()), 3 * most_in_window)
      << mapped.size() << " mapped, at most " << most_in_window
      << " in the window";
  // The depth precision follows the triangulation angle: the landmarks
  // seen over a few degrees are where the simulator put them, the rest
  // (most of them, seen over less than 1 deg) can be metres off.
  const auto median_above = [&](double min_deg) {
    std::vector<double> e;
    for (const auto& [angle, error] : by_angle) {
      if (angle >= min_deg) e.push_back(error);
    }
    std::sort(e.begin(), e.end());
    return e.empty() ? 1e9 : e[e.size() / 2];
  };
  const double all = median_above(0.0);
  const double wide = median_above(5.0);
  EXPECT_LT(wide, 0.15) << "median error at >= 5 deg " << wide << " m";
  EXPECT_LT(wide, 0.5 * all) << "median error of all " << all << " m";
}

}  // namespace
}  // namespace vio
