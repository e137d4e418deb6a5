#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "geometry/so3.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

// The truth at the last ground-truth stamp not after t_ns.
const StampedState& TruthAt(const Simulation& sim, int64_t t_ns) {
  const StampedState* s = &sim.ground_truth.front();
  for (const StampedState& g : sim.ground_truth) {
    if (g.t_ns > t_ns) break;
    s = &g;
  }
  return *s;
}

// After a failed step the window restarts from that step's prediction: the
// last accepted state carried to the frame by the IMU, the tilt prior
// centred there (issue 11's review asked whether the last accepted state
// itself would be the better centre; docs/recorded_flights.md measures that
// it is not). So the rotation from the previous output to the restart state
// is the true rotation over the interval, up to gyroscope noise and bias
// error, while the previous output itself misses that rotation whole.
TEST(EstimatorReset, RestartsFromTheLastAcceptedStateCarriedByTheImu) {
  const SimulatorOptions sim_options = testing::ShortSimulation(12.0, false);
  const Simulation sim = Simulate(sim_options);
  EstimatorOptions options = testing::OptionsFor(sim_options);
  // A jump rule far tighter than the shipped 1 m provokes resets.
  options.failure.max_position_jump_m = 0.05;
  const testing::SimReplay r = testing::ReplaySimulation(sim, options);
  ASSERT_GE(r.summary.resets, 1);
  int checked = 0;
  double worst_rad = 0.0;     // restart vs the IMU-carried truth
  double largest_rad = 0.0;   // the true rotation over the interval
  for (const ResetEvent& e : r.summary.reset_log) {
    const auto it = std::find_if(
        r.outputs.begin(), r.outputs.end(),
        [&](const EstimatorOutput& o) { return o.t_ns == e.t_ns; });
    if (it == r.outputs.begin() || it == r.outputs.end()) continue;
    const EstimatorOutput& restart = *it;
    const EstimatorOutput& previous = *(it - 1);
    if (!previous.processed || !previous.initialized) continue;
    const Eigen::Quaterniond true_step =
        TruthAt(sim, previous.t_ns).q_w_b.conjugate() *
        TruthAt(sim, restart.t_ns).q_w_b;
    const Eigen::Quaterniond estimated_step =
        previous.q_w_b.conjugate() * restart.q_w_b;
    worst_rad = std::max(
        worst_rad, Log(estimated_step.conjugate() * true_step).norm());
    largest_rad = std::max(largest_rad, Log(true_step).norm());
    ++checked;
  }
  std::printf("resets %lld, checked %d: restart vs IMU-carried truth at most "
              "%.4f deg; true rotation over the interval up to %.3f deg\n",
              static_cast<long long>(r.summary.resets), checked,
              worst_rad * 180.0 / M_PI, largest_rad * 180.0 / M_PI);
  ASSERT_GE(checked, 1);
  // Gyroscope noise over one frame interval is ~1e-4 rad; centring on the
  // previous output would miss by the true rotation, checked to be far
  // above the bound.
  EXPECT_LT(worst_rad, 5e-4);
  EXPECT_GT(largest_rad, 10 * 5e-4);
}

}  // namespace
}  // namespace vio
