// CutSimulation (test/testing/cut_simulation.h): the cut is the original
// from t0 on, sample for sample, so that init_benchmark's same-sequence
// comparison (docs/initialisation.md, "End to end") replays one noise
// realisation twice and only the start differs.

#include "test/testing/cut_simulation.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

#include "dataset/simulator.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

// 3 s, stereo (both cameras' observations), with outliers; moving from 0.5 s
// on (0.5 s still, 0.5 s blend), as init_benchmark cuts after the blend.
Simulation Original() {
  SimulatorOptions o = testing::ShortSimulation(3.0, true);
  o.motion.still_duration_s = 0.5;
  o.motion.blend_duration_s = 0.5;
  o.camera.outlier_fraction = 0.05;
  return Simulate(o);
}

// t0 between two IMU samples and two frames, 1.23 s in.
int64_t CutTime(const Simulation& sim) {
  return sim.imu.front().t_ns + 1230000001;
}

TEST(CutSimulation, ImuAndTruthAreTheOriginalsFromT0On) {
  const Simulation sim = Original();
  const int64_t t0 = CutTime(sim);
  const Simulation cut = testing::CutSimulation(sim, t0);
  size_t first = 0;
  while (sim.imu[first].t_ns < t0) ++first;
  ASSERT_GT(first, 0u);
  ASSERT_EQ(cut.imu.size(), sim.imu.size() - first);
  ASSERT_EQ(cut.imu_true.size(), cut.imu.size());
  for (size_t i = 0; i < cut.imu.size(); ++i) {
    const ImuSample& a = cut.imu[i];
    const ImuSample& b = sim.imu[first + i];
    ASSERT_EQ(a.t_ns, b.t_ns) << i;
    ASSERT_EQ(a.acc, b.acc) << i;  // bit for bit: the same noise
    ASSERT_EQ(a.gyr, b.gyr) << i;
    ASSERT_EQ(cut.imu_true[i].acc, sim.imu_true[first + i].acc) << i;
  }
  ASSERT_EQ(cut.ground_truth.size(), sim.ground_truth.size() - first);
  for (size_t i = 0; i < cut.ground_truth.size(); ++i) {
    ASSERT_EQ(cut.ground_truth[i].t_ns, sim.ground_truth[first + i].t_ns);
    ASSERT_EQ(cut.ground_truth[i].p_w_b, sim.ground_truth[first + i].p_w_b);
  }
  EXPECT_EQ(cut.options.start_time_ns, sim.imu[first].t_ns);
  EXPECT_EQ(cut.summary.imu_samples, static_cast<int64_t>(cut.imu.size()));
}

TEST(CutSimulation, FramesAreTheOriginalsFromT0On) {
  const Simulation sim = Original();
  const int64_t t0 = CutTime(sim);
  const Simulation cut = testing::CutSimulation(sim, t0);
  size_t first = 0;
  while (sim.frames[first].t_ns < t0) ++first;
  ASSERT_GT(first, 0u);
  ASSERT_EQ(cut.frames.size(), sim.frames.size() - first);
  ASSERT_EQ(cut.is_outlier.size(), cut.frames.size());
  int64_t outliers = 0;
  for (size_t i = 0; i < cut.frames.size(); ++i) {
    const FeatureFrame& a = cut.frames[i];
    const FeatureFrame& b = sim.frames[first + i];
    ASSERT_EQ(a.t_ns, b.t_ns);
    ASSERT_EQ(a.observations.size(), b.observations.size()) << i;
    for (size_t j = 0; j < a.observations.size(); ++j) {
      ASSERT_EQ(a.observations[j].feature_id, b.observations[j].feature_id);
      ASSERT_EQ(a.observations[j].camera, b.observations[j].camera);
      ASSERT_EQ(a.observations[j].uv, b.observations[j].uv);
      ASSERT_EQ(cut.is_outlier[i][j], sim.is_outlier[first + i][j]);
      outliers += cut.is_outlier[i][j] ? 1 : 0;
    }
  }
  EXPECT_GT(outliers, 0);
  EXPECT_EQ(cut.summary.outliers, outliers);
  EXPECT_EQ(cut.summary.frames, static_cast<int64_t>(cut.frames.size()));
}

// What the estimator receives: the cut's first frame has no previous one
// (image velocities zero, as in a trimmed folder); from its second frame on
// the prepared frames are the original's.
TEST(CutSimulation, PreparedFramesMatchFromTheSecondCutFrameOn) {
  const Simulation sim = Original();
  const Simulation cut = testing::CutSimulation(sim, CutTime(sim));
  const testing::PreparedSimulation whole = testing::Prepare(sim);
  const testing::PreparedSimulation part = testing::Prepare(cut);
  const size_t first = whole.frames.size() - part.frames.size();
  bool moving = false;  // the original's first cut frame has velocities
  for (const FeatureObservation& o : whole.frames[first].observations) {
    moving = moving || o.velocity.norm() > 0.0;
  }
  EXPECT_TRUE(moving);
  for (const FeatureObservation& o : part.frames[0].observations) {
    EXPECT_EQ(o.velocity.norm(), 0.0);
  }
  for (size_t i = 1; i < part.frames.size(); ++i) {
    const FeatureFrame& a = part.frames[i];
    const FeatureFrame& b = whole.frames[first + i];
    ASSERT_EQ(a.t_ns, b.t_ns);
    ASSERT_EQ(a.observations.size(), b.observations.size()) << i;
    for (size_t j = 0; j < a.observations.size(); ++j) {
      ASSERT_EQ(a.observations[j].feature_id, b.observations[j].feature_id);
      ASSERT_EQ(a.observations[j].xy, b.observations[j].xy);
      ASSERT_EQ(a.observations[j].velocity, b.observations[j].velocity)
          << "frame " << i << " observation " << j;
    }
  }
}

TEST(CutSimulation, RefusesACutPastTheEnd) {
  Simulation sim = Original();
  EXPECT_THROW(testing::CutSimulation(sim, sim.imu.back().t_ns + 1),
               std::invalid_argument);
  // IMU samples but no frame after t0: the last 0.5 s without frames.
  while (sim.frames.back().t_ns > sim.imu.back().t_ns - 500000000) {
    sim.frames.pop_back();
    sim.is_outlier.pop_back();
  }
  EXPECT_THROW(testing::CutSimulation(sim, sim.frames.back().t_ns + 1),
               std::invalid_argument);
  EXPECT_NO_THROW(testing::CutSimulation(sim, sim.frames.back().t_ns));
}

}  // namespace
}  // namespace vio
