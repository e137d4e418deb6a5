#include "dataset/simulator.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "dataset/sim_features.h"

namespace vio {
namespace {

// Independent random streams, so that e.g. changing the camera options does
// not change the IMU noise of the same seed.
enum Stream : uint32_t {
  kImuStream = 1,
  kLandmarkStream = 2,
  kCameraStream = 3
};

uint32_t StreamSeed(uint32_t seed, Stream stream) {
  std::seed_seq sequence{seed, static_cast<uint32_t>(stream)};
  uint32_t out = 0;
  sequence.generate(&out, &out + 1);
  return out;
}

CameraCalibration EurocCamera(const double (&T_b_c)[12],
                              const Eigen::Vector4d& intrinsics,
                              const Eigen::Vector4d& distortion) {
  CameraCalibration c;
  c.width = 752;
  c.height = 480;
  c.rate_hz = 20.0;
  c.fx = intrinsics[0];
  c.fy = intrinsics[1];
  c.cx = intrinsics[2];
  c.cy = intrinsics[3];
  c.distortion = DistortionModel::kRadialTangential;
  c.distortion_coefficients = distortion;
  const Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> T(T_b_c);
  c.q_b_c = Eigen::Quaterniond(Eigen::Matrix3d(T.leftCols<3>())).normalized();
  c.t_b_c = T.col(3);
  return c;
}

bool Fail(std::string* message, const std::string& text) {
  *message = text;
  return false;
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }
bool Fraction(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

bool ValidateCamera(const SimCameraOptions& c, std::string* message) {
  std::string m;
  if (!c.cam0.Validate(&m)) return Fail(message, "camera.cam0." + m);
  if (c.stereo && !c.cam1.Validate(&m))
    return Fail(message, "camera.cam1." + m);
  if (!(std::isfinite(c.pixel_noise_px) && c.pixel_noise_px >= 0.0)) {
    return Fail(message, "camera.pixel_noise_px must be >= 0");
  }
  if (c.max_features_per_frame < 1) {
    return Fail(message, "camera.max_features_per_frame must be >= 1");
  }
  if (!(std::isfinite(c.min_feature_distance_px) &&
        c.min_feature_distance_px >= 0.0)) {
    return Fail(message, "camera.min_feature_distance_px must be >= 0");
  }
  if (!Fraction(c.track_drop_probability)) {
    return Fail(message, "camera.track_drop_probability must be in [0, 1]");
  }
  if (!Fraction(c.outlier_fraction)) {
    return Fail(message, "camera.outlier_fraction must be in [0, 1]");
  }
  if (!(std::isfinite(c.time_offset_s) && std::abs(c.time_offset_s) < 1.0)) {
    return Fail(message, "camera.time_offset_s must be within +-1 s");
  }
  return true;
}

}  // namespace

CameraCalibration EurocCam0Calibration() {
  const double T_b_c[12] = {
      0.0148655429818,  -0.999880929698,  0.00414029679422, -0.0216401454975,
      0.999557249008,   0.0149672133247,  0.025715529948,   -0.064676986768,
      -0.0257744366974, 0.00375618835797, 0.999660727178,   0.00981073058949};
  return EurocCamera(T_b_c, {458.654, 457.296, 367.215, 248.375},
                     {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05});
}

CameraCalibration EurocCam1Calibration() {
  const double T_b_c[12] = {
      0.0125552670891,  -0.999755099723, 0.0182237714554, -0.0198435579556,
      0.999598781151,   0.0130119051815, 0.0251588363115, 0.0453689425024,
      -0.0253898008918, 0.0179005838253, 0.999517347078,  0.00786212447038};
  return EurocCamera(T_b_c, {457.587, 456.134, 379.999, 255.238},
                     {-0.28368365, 0.07451284, -0.00010473, -3.55590700e-05});
}

bool SimulatorOptions::Validate(std::string* message) const {
  // 600 s is longer than any EuRoC sequence and keeps memory < ~200 MB.
  if (!(Positive(duration_s) && duration_s <= 600.0)) {
    return Fail(message, "duration_s must be in (0, 600]");
  }
  if (start_time_ns < 0 || start_time_ns > (int64_t{1} << 62)) {
    return Fail(message, "start_time_ns must be in [0, 2^62]");
  }
  if (!Positive(gravity_m_s2)) return Fail(message, "gravity_m_s2 must be > 0");
  std::string m;
  if (!motion.Validate(&m)) return Fail(message, "motion." + m);
  if (!Positive(imu.rate_hz)) return Fail(message, "imu.rate_hz must be > 0");
  if (!imu.noise.Validate(&m)) return Fail(message, "imu." + m);
  if (!imu.initial_accelerometer_bias.allFinite() ||
      !imu.initial_gyroscope_bias.allFinite()) {
    return Fail(message, "imu.initial biases must be finite");
  }
  if (!ValidateCamera(camera, message)) return false;
  if (!Positive(room.half_length_x_m) || !Positive(room.half_width_y_m) ||
      !Positive(room.height_m)) {
    return Fail(message, "room sizes must be > 0");
  }
  if (room.landmarks < 1) return Fail(message, "room.landmarks must be >= 1");
  constexpr double kClearance = 0.5;  // [m]
  if (motion.radius_x_m + kClearance > room.half_length_x_m ||
      motion.radius_y_m + kClearance > room.half_width_y_m ||
      motion.height_m - motion.height_amplitude_m < kClearance ||
      motion.height_m + motion.height_amplitude_m + kClearance >
          room.height_m) {
    return Fail(message,
                "motion must stay 0.5 m inside the room (radii, height +- "
                "amplitude against room sizes)");
  }
  if (motion.shape == SimShape::kCircle &&
      motion.radius_y_m + kClearance > room.half_length_x_m) {
    return Fail(message,
                "motion.radius_y_m (the circle's radius) must stay "
                "0.5 m inside the room");
  }
  if (motion.shape == SimShape::kLine &&
      motion.start_phase_s + duration_s > motion.lap_period_s) {
    return Fail(message,
                "motion.start_phase_s + duration_s must be <= "
                "motion.lap_period_s for the line (one pass)");
  }
  return true;
}

namespace {

// Ground truth at t_ns: the trajectory's pose and velocity, these biases.
StampedState TruthAt(const TrajectorySource& trajectory, int64_t start_ns,
                     int64_t t_ns, const Eigen::Vector3d& b_a,
                     const Eigen::Vector3d& b_g) {
  const SimState s = trajectory.At(static_cast<double>(t_ns - start_ns) * 1e-9);
  StampedState truth;
  truth.t_ns = t_ns;
  truth.p_w_b = s.p_w_b;
  truth.q_w_b = s.q_w_b;
  truth.v_w = s.v_w;
  truth.b_a = b_a;
  truth.b_g = b_g;
  return truth;
}

// The exact IMU reading at t_ns (no bias, no noise).
ImuSample ExactImu(const TrajectorySource& trajectory, int64_t start_ns,
                   int64_t t_ns, double gravity) {
  const SimState s = trajectory.At(static_cast<double>(t_ns - start_ns) * 1e-9);
  ImuSample exact;
  exact.t_ns = t_ns;
  exact.acc = s.q_w_b.conjugate() * (s.a_w - Eigen::Vector3d(0, 0, -gravity));
  exact.gyr = s.w_b;
  return exact;
}

void PassRecordedImu(const TrajectorySource& trajectory,
                     const std::vector<ImuSample>& recorded, Simulation* sim) {
  const SimulatorOptions& o = sim->options;
  const int64_t end_ns = o.start_time_ns + std::llround(o.duration_s * 1e9);
  for (const ImuSample& sample : recorded) {
    if (sample.t_ns < o.start_time_ns || sample.t_ns > end_ns) continue;
    sim->imu.push_back(sample);
    sim->imu_true.push_back(
        ExactImu(trajectory, o.start_time_ns, sample.t_ns, o.gravity_m_s2));
    sim->ground_truth.push_back(TruthAt(trajectory, o.start_time_ns,
                                        sample.t_ns, Eigen::Vector3d::Zero(),
                                        Eigen::Vector3d::Zero()));
  }
  if (sim->imu.size() < 2) {
    throw std::invalid_argument(
        "simulation: the recorded IMU has fewer than 2 samples in the span");
  }
}

void SimulateImu(const TrajectorySource& trajectory, Simulation* sim) {
  const SimulatorOptions& o = sim->options;
  const int64_t dt_ns = std::llround(1e9 / o.imu.rate_hz);
  const double dt = static_cast<double>(dt_ns) * 1e-9;
  const int64_t n = static_cast<int64_t>(std::floor(o.duration_s / dt)) + 1;
  const ImuNoise& noise = o.imu.noise;
  std::mt19937 rng(StreamSeed(o.seed, kImuStream));
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian = [&] {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    return Eigen::Vector3d(x, y, z);
  };
  Eigen::Vector3d b_a = o.imu.initial_accelerometer_bias;
  Eigen::Vector3d b_g = o.imu.initial_gyroscope_bias;
  for (int64_t k = 0; k < n; ++k) {
    const int64_t t_ns = o.start_time_ns + k * dt_ns;
    const ImuSample exact =
        ExactImu(trajectory, o.start_time_ns, t_ns, o.gravity_m_s2);
    ImuSample measured = exact;
    measured.acc += b_a;
    measured.gyr += b_g;
    const StampedState truth =
        TruthAt(trajectory, o.start_time_ns, t_ns, b_a, b_g);
    if (o.imu.add_noise) {
      // Discrete white noise sigma / sqrt(dt); bias walk sigma * sqrt(dt).
      measured.acc +=
          noise.accelerometer_noise_density / std::sqrt(dt) * gaussian();
      measured.gyr +=
          noise.gyroscope_noise_density / std::sqrt(dt) * gaussian();
      b_a += noise.accelerometer_random_walk * std::sqrt(dt) * gaussian();
      b_g += noise.gyroscope_random_walk * std::sqrt(dt) * gaussian();
    }
    sim->imu.push_back(measured);
    sim->imu_true.push_back(exact);
    sim->ground_truth.push_back(truth);
  }
}

// Camera stamps from the start at cam0's rate, up to last_ns.
std::vector<int64_t> RegularStamps(const SimulatorOptions& o, int64_t last_ns) {
  const int64_t period_ns = std::llround(1e9 / o.camera.cam0.rate_hz);
  std::vector<int64_t> stamps;
  for (int64_t t_ns = o.start_time_ns; t_ns <= last_ns; t_ns += period_ns) {
    stamps.push_back(t_ns);
  }
  return stamps;
}

void SimulateCameras(const TrajectorySource& trajectory,
                     const SimulationInputs& inputs, Simulation* sim) {
  const SimulatorOptions& o = sim->options;
  if (inputs.landmarks_w != nullptr) {
    sim->landmarks_w = *inputs.landmarks_w;
  } else {
    std::mt19937 landmark_rng(StreamSeed(o.seed, kLandmarkStream));
    sim->landmarks_w = MakeRoomLandmarks(o.room, &landmark_rng);
  }
  if (sim->landmarks_w.empty()) {
    throw std::invalid_argument("simulation: no landmarks");
  }
  SimFeatureTracker tracker(o.camera, &sim->landmarks_w,
                            StreamSeed(o.seed, kCameraStream));
  const int64_t t_d_ns = std::llround(o.camera.time_offset_s * 1e9);
  const int64_t first_ns = sim->ground_truth.front().t_ns;
  const int64_t end_ns = sim->ground_truth.back().t_ns;
  const std::vector<int64_t> stamps = inputs.frame_stamps_ns != nullptr
                                          ? *inputs.frame_stamps_ns
                                          : RegularStamps(o, end_ns - t_d_ns);
  // Frames on the camera clock whose exposure (IMU clock) lies within the
  // IMU span.
  for (size_t k = 0; k < stamps.size(); ++k) {
    const int64_t t_ns = stamps[k];
    if (k > 0 && t_ns <= stamps[k - 1]) {
      throw std::invalid_argument("simulation: frame stamps must increase");
    }
    if (t_ns + t_d_ns < first_ns || t_ns + t_d_ns > end_ns) continue;
    const SimState s = trajectory.At(
        static_cast<double>(t_ns + t_d_ns - o.start_time_ns) * 1e-9);
    FeatureFrame frame;
    std::vector<bool> outliers;
    tracker.Track(t_ns, s.q_w_b, s.p_w_b, &frame, &outliers);
    sim->frames.push_back(std::move(frame));
    sim->is_outlier.push_back(std::move(outliers));
  }
  sim->landmark_of_feature = tracker.landmark_of_feature();
}

SimulationSummary Summarise(const Simulation& sim) {
  SimulationSummary s;
  s.imu_samples = static_cast<int64_t>(sim.imu.size());
  s.duration_s =
      static_cast<double>(sim.imu.back().t_ns - sim.imu.front().t_ns) * 1e-9;
  s.frames = static_cast<int64_t>(sim.frames.size());
  s.tracks = static_cast<int64_t>(sim.landmark_of_feature.size());
  int64_t cam0 = 0;
  for (size_t i = 0; i < sim.frames.size(); ++i) {
    int in_cam0 = 0;
    for (size_t j = 0; j < sim.frames[i].observations.size(); ++j) {
      ++s.observations;
      if (sim.is_outlier[i][j]) ++s.outliers;
      if (sim.frames[i].observations[j].camera == 0) ++in_cam0;
    }
    cam0 += in_cam0;
    s.max_cam0_observations = std::max(s.max_cam0_observations, in_cam0);
  }
  if (s.frames > 0) {
    s.mean_cam0_observations = static_cast<double>(cam0) / s.frames;
  }
  if (s.tracks > 0) s.mean_track_length = static_cast<double>(cam0) / s.tracks;
  return s;
}

}  // namespace

Simulation Simulate(const SimulatorOptions& options) {
  return Simulate(options, SimulationInputs());
}

Simulation Simulate(const SimulatorOptions& options,
                    const SimulationInputs& inputs) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("simulator options: " + message);
  }
  Simulation sim;
  sim.options = options;
  const SimTrajectory analytic(options.motion);
  const TrajectorySource& trajectory =
      inputs.trajectory != nullptr ? *inputs.trajectory : analytic;
  if (inputs.recorded_imu != nullptr) {
    PassRecordedImu(trajectory, *inputs.recorded_imu, &sim);
  } else {
    SimulateImu(trajectory, &sim);
  }
  SimulateCameras(trajectory, inputs, &sim);
  sim.summary = Summarise(sim);
  return sim;
}

}  // namespace vio
