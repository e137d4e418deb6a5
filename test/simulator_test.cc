#include "dataset/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "geometry/so3.h"

namespace vio {
namespace {

// A shorter sequence keeps each test well under a second.
SimulatorOptions ShortOptions(double duration_s) {
  SimulatorOptions options;
  options.duration_s = duration_s;
  return options;
}

// Sample standard deviation of every entry of `values` (3-vectors, pooled).
double PooledStd(const std::vector<Eigen::Vector3d>& values) {
  double sum = 0.0, sum2 = 0.0;
  for (const Eigen::Vector3d& v : values) {
    sum += v.sum();
    sum2 += v.squaredNorm();
  }
  const double n = 3.0 * values.size();
  return std::sqrt((sum2 - sum * sum / n) / (n - 1.0));
}

TEST(Simulator, ImuNoiseAndBiasWalkMatchTheConfiguredDensities) {
  const Simulation sim = Simulate(ShortOptions(40.0));
  const ImuNoise& noise = sim.options.imu.noise;
  const double dt = 1.0 / sim.options.imu.rate_hz;
  std::vector<Eigen::Vector3d> n_a, n_g, walk_a, walk_g;
  for (size_t k = 0; k < sim.imu.size(); ++k) {
    const StampedState& truth = sim.ground_truth[k];
    n_a.push_back(sim.imu[k].acc - sim.imu_true[k].acc - truth.b_a);
    n_g.push_back(sim.imu[k].gyr - sim.imu_true[k].gyr - truth.b_g);
    if (k > 0) {
      walk_a.push_back(truth.b_a - sim.ground_truth[k - 1].b_a);
      walk_g.push_back(truth.b_g - sim.ground_truth[k - 1].b_g);
    }
  }
  // 3 x 8000 samples: the sample std's relative standard error is
  // 1/sqrt(2 n) = 0.46 %, so 3 % is more than 6 standard errors.
  constexpr double kTolerance = 0.03;
  EXPECT_NEAR(
      PooledStd(n_a) / (noise.accelerometer_noise_density / std::sqrt(dt)), 1.0,
      kTolerance);
  EXPECT_NEAR(PooledStd(n_g) / (noise.gyroscope_noise_density / std::sqrt(dt)),
              1.0, kTolerance);
  EXPECT_NEAR(
      PooledStd(walk_a) / (noise.accelerometer_random_walk * std::sqrt(dt)),
      1.0, kTolerance);
  EXPECT_NEAR(PooledStd(walk_g) / (noise.gyroscope_random_walk * std::sqrt(dt)),
              1.0, kTolerance);
  // The biases start where configured, not at zero.
  EXPECT_EQ(sim.ground_truth.front().b_a,
            sim.options.imu.initial_accelerometer_bias);
  EXPECT_GT(sim.ground_truth.front().b_g.norm(), 0.01);
}

TEST(Simulator, WithoutNoiseTheImuIsExactAndTheBiasesConstant) {
  SimulatorOptions options = ShortOptions(5.0);
  options.imu.add_noise = false;
  const Simulation sim = Simulate(options);
  for (size_t k = 0; k < sim.imu.size(); k += 50) {
    EXPECT_EQ(sim.ground_truth[k].b_a, options.imu.initial_accelerometer_bias);
    EXPECT_LT((sim.imu[k].acc - sim.imu_true[k].acc -
               options.imu.initial_accelerometer_bias)
                  .norm(),
              1e-12);
  }
  // At rest (the first 2 s) the accelerometer feels gravity along body x.
  EXPECT_LT((sim.imu_true[10].acc - Eigen::Vector3d(9.81, 0, 0)).norm(), 1e-9);
  EXPECT_EQ(sim.imu_true[10].gyr, Eigen::Vector3d::Zero());
}

// The ground-truth state at each stamp, for looking up camera stamps.
std::map<int64_t, StampedState> ByStamp(const Simulation& sim) {
  std::map<int64_t, StampedState> states;
  for (const StampedState& s : sim.ground_truth) states[s.t_ns] = s;
  return states;
}

// Reprojection residuals [px] of the inlier observations, the pose taken at
// camera stamp + `shift_ns` from the ground truth.
std::vector<Eigen::Vector2d> Residuals(const Simulation& sim,
                                       int64_t shift_ns) {
  const std::map<int64_t, StampedState> states = ByStamp(sim);
  const CameraModel models[2] = {CameraModel(sim.options.camera.cam0),
                                 CameraModel(sim.options.camera.cam1)};
  std::vector<Eigen::Vector2d> residuals;
  for (size_t i = 0; i < sim.frames.size(); ++i) {
    const auto it = states.find(sim.frames[i].t_ns + shift_ns);
    if (it == states.end()) continue;
    const StampedState& s = it->second;
    for (size_t j = 0; j < sim.frames[i].observations.size(); ++j) {
      if (sim.is_outlier[i][j]) continue;
      const FeatureObservation& obs = sim.frames[i].observations[j];
      const CameraModel& model = models[obs.camera];
      const CameraCalibration& c = model.calibration();
      const Eigen::Vector3d& p_w =
          sim.landmarks_w[sim.landmark_of_feature[obs.feature_id]];
      // p_c = R_b_c^T (R_w_b^T (p_w - p_w_b) - t_b_c)
      const Eigen::Vector3d p_c =
          c.q_b_c.conjugate() *
          (s.q_w_b.conjugate() * (p_w - s.p_w_b) - c.t_b_c);
      Eigen::Vector2d uv;
      EXPECT_TRUE(model.Project(p_c, &uv));
      residuals.push_back(obs.uv - uv);
    }
  }
  return residuals;
}

TEST(Simulator, ObservationsReprojectOntoTheGroundTruthWithinPixelNoise) {
  SimulatorOptions options = ShortOptions(15.0);
  options.camera.stereo = true;
  const Simulation sim = Simulate(options);
  const std::vector<Eigen::Vector2d> r = Residuals(sim, 0);
  ASSERT_GT(r.size(), 10000u);
  double sum2 = 0.0, worst = 0.0;
  for (const Eigen::Vector2d& e : r) {
    sum2 += e.squaredNorm();
    worst = std::max(worst, e.cwiseAbs().maxCoeff());
  }
  const double rms = std::sqrt(sum2 / (2.0 * r.size()));
  // > 2e4 residuals per axis: the rms is within 2 % of sigma at > 4 standard
  // errors; no residual beyond the 4 sigma (+1 px) border margin's reach.
  EXPECT_NEAR(rms, options.camera.pixel_noise_px, 0.02);
  EXPECT_LT(worst, 6.0 * options.camera.pixel_noise_px);

  options.camera.pixel_noise_px = 0.0;
  const Simulation exact = Simulate(options);
  for (const Eigen::Vector2d& e : Residuals(exact, 0)) {
    ASSERT_LT(e.norm(), 1e-9);
  }
}

TEST(Simulator, TimeOffsetShiftsTheExposureOntoTheImuClock) {
  SimulatorOptions options = ShortOptions(10.0);
  options.camera.pixel_noise_px = 0.0;
  options.camera.time_offset_s = 0.015;  // a multiple of the IMU period
  const Simulation sim = Simulate(options);
  double at_offset = 0.0, at_stamp = 0.0;
  for (const Eigen::Vector2d& e : Residuals(sim, 15000000)) {
    at_offset = std::max(at_offset, e.norm());
  }
  for (const Eigen::Vector2d& e : Residuals(sim, 0)) {
    at_stamp = std::max(at_stamp, e.norm());
  }
  EXPECT_LT(at_offset, 1e-9);
  EXPECT_GT(at_stamp, 1.0);  // 15 ms of motion moves pixels visibly
}

TEST(Simulator, TracksLookLikeAKltTrackersAndRespectTheCap) {
  const Simulation sim = Simulate(ShortOptions(20.0));
  const SimulationSummary& s = sim.summary;
  EXPECT_EQ(s.frames, 401);  // 0 to 20 s inclusive at 20 Hz
  EXPECT_LE(s.max_cam0_observations, sim.options.camera.max_features_per_frame);
  EXPECT_GT(s.mean_cam0_observations,
            0.8 * sim.options.camera.max_features_per_frame);
  // Tracks of a few to a few tens of frames; new ids keep appearing.
  EXPECT_GT(s.mean_track_length, 8.0);
  EXPECT_LT(s.mean_track_length, 40.0);
  EXPECT_GT(s.tracks, 5 * sim.options.camera.max_features_per_frame);
  EXPECT_EQ(s.outliers, 0);
}

TEST(Simulator, StereoSharesFeatureIdsAndOutliersFollowTheirFraction) {
  SimulatorOptions options = ShortOptions(10.0);
  options.camera.stereo = true;
  options.camera.outlier_fraction = 0.1;
  const Simulation sim = Simulate(options);
  int64_t cam0 = 0, cam1_shared = 0;
  for (const FeatureFrame& frame : sim.frames) {
    std::map<int64_t, int> cameras_of_id;
    for (const FeatureObservation& obs : frame.observations) {
      cameras_of_id[obs.feature_id] |= 1 << obs.camera;
    }
    for (const auto& [id, mask] : cameras_of_id) {
      EXPECT_TRUE(mask & 1) << "cam1 observes only cam0's tracks";
      ++cam0;
      if (mask == 3) ++cam1_shared;
    }
  }
  EXPECT_GT(static_cast<double>(cam1_shared) / cam0, 0.7);
  const double fraction =
      static_cast<double>(sim.summary.outliers) / sim.summary.observations;
  // ~5e4 observations: the binomial std of the fraction is 0.0013.
  EXPECT_NEAR(fraction, 0.1, 0.01);
}

TEST(Simulator, InvalidOptionsNameTheField) {
  SimulatorOptions options;
  options.motion.radius_x_m = 7.0;
  std::string message;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message.rfind("motion must stay 0.5 m inside the room", 0), 0u);
  options = SimulatorOptions();
  options.camera.outlier_fraction = 1.5;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "camera.outlier_fraction must be in [0, 1]");
  EXPECT_THROW(Simulate(options), std::invalid_argument);
  options = SimulatorOptions();
  options.duration_s = 601.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "duration_s must be in (0, 600]");
}

}  // namespace
}  // namespace vio
