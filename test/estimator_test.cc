#include "estimator/estimator.h"

#include <gtest/gtest.h>

#include "test/testing/sim_replay.h"

namespace vio {
namespace {

using testing::ReplaySimulation;

void Report(const char* name, const testing::SimReplay& r) {
  double max_solve = 0.0, sum = 0.0;
  for (double t : r.summary.solver_time_s) {
    max_solve = std::max(max_solve, t);
    sum += t;
  }
  std::printf(
      "%s: frames %lld processed %lld keyframes %lld resets %lld ATE %.4f m "
      "RPE %.4f m |db_a| %.4f |db_g| %.5f outliers %lld mean solve %.2f ms "
      "max %.2f ms\n",
      name, (long long)r.summary.frames, (long long)r.summary.frames_processed,
      (long long)r.summary.keyframes, (long long)r.summary.resets, r.ate_rmse_m,
      r.rpe_rmse_m, r.final_b_a_error, r.final_b_g_error,
      (long long)r.summary.outlier_landmarks_removed,
      1e3 * sum / std::max<size_t>(1, r.summary.solver_time_s.size()),
      1e3 * max_solve);
}

TEST(Estimator, MonoSimulationWithStillStart) {
  const SimulatorOptions sim = testing::ShortSimulation(12.0, false);
  const testing::SimReplay r =
      ReplaySimulation(Simulate(sim), testing::OptionsFor(sim));
  Report("mono", r);
  EXPECT_EQ(r.summary.resets, 0);
}

TEST(Estimator, StereoSimulationWithStillStart) {
  const SimulatorOptions sim = testing::ShortSimulation(12.0, true);
  const testing::SimReplay r =
      ReplaySimulation(Simulate(sim), testing::OptionsFor(sim));
  Report("stereo", r);
  EXPECT_EQ(r.summary.resets, 0);
}

}  // namespace
}  // namespace vio
