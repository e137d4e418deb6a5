#ifndef VIO_DATASET_SIMULATOR_H_
#define VIO_DATASET_SIMULATOR_H_

// A built-in sequence that needs no download: a body flying the analytic
// trajectory of dataset/sim_trajectory.h through a room whose walls, floor
// and ceiling carry point landmarks, seen by EuRoC-like cameras and felt by an
// EuRoC-like IMU.
//
// IMU (rate_hz, default 200 Hz), on the IMU clock:
//   acc = R_w_b^T (a_w - g_w) + b_a + n_a,   g_w = (0, 0, -g)
//   gyr = w_b + b_g + n_g
// n ~ N(0, sigma^2 / dt) per axis from the noise densities, and the biases
// walk b += N(0, sigma_rw^2 dt) after each sample, starting at non-zero
// values (Kalibr convention, DESIGN.md). With add_noise off both vanish and
// the biases stay at their initial values.
//
// Cameras (rate of cam0's calibration, default 20 Hz), stamped on the camera
// clock: the frame stamped t_cam shows the scene at IMU time t_cam + t_d
// (t_d = time_offset_s). Each frame imitates a KLT tracker: tracks of cam0
// continue while their landmark stays in view (and survives a per-frame drop
// probability); when fewer than max_features_per_frame remain, new tracks
// start on visible landmarks at least min_feature_distance_px from every other
// feature, each with a new feature id. A stereo cam1 observes the same tracks
// under the same ids when it sees them. Pixels are distorted (the camera
// model's Project) plus N(0, pixel_noise_px^2) per axis; a fraction of
// observations is replaced by outliers uniform over the image.
//
// Deterministic: the same options (seed included) give the same Simulation,
// and WriteSimulationFolder the same bytes.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "dataset/sim_trajectory.h"
#include "dataset/trajectory.h"
#include "dataset/trajectory_source.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"
#include "preintegration/imu_types.h"

namespace vio {

// EuRoC's VI-Sensor cameras (V1_01 sensor.yaml): intrinsics, radial-
// tangential distortion, 752x480 at 20 Hz, T_BS.
CameraCalibration EurocCam0Calibration();
CameraCalibration EurocCam1Calibration();

struct SimImuOptions {
  double rate_hz = 200.0;  // [Hz]
  bool add_noise = true;   // white noise and bias random walk
  ImuNoise noise;          // densities (default: EuRoC's ADIS16448)
  // Biases at the start (near EuRoC V1_01's ground-truth values).
  Eigen::Vector3d initial_accelerometer_bias{-0.018, 0.066, 0.031};  // [m/s^2]
  Eigen::Vector3d initial_gyroscope_bias{-0.0022, 0.0215, 0.0770};   // [rad/s]
};

struct SimCameraOptions {
  bool stereo = false;  // false: cam0 only; true: cam0 and cam1
  CameraCalibration cam0 = EurocCam0Calibration();
  CameraCalibration cam1 = EurocCam1Calibration();
  double pixel_noise_px = 1.0;            // std per axis [px]
  int max_features_per_frame = 150;       // cam0 tracks per frame
  double min_feature_distance_px = 20.0;  // between new and other features
  double track_drop_probability = 0.03;   // per track and frame [-]
  double outlier_fraction = 0.0;          // of all observations [-]
  double time_offset_s = 0.0;             // t_d: t_imu = t_cam + t_d [s]
};

// A box room, floor at z = 0, centred on the trajectory's ellipse.
struct SimRoomOptions {
  double half_length_x_m = 7.0;  // walls at x = +-half_length_x_m [m]
  double half_width_y_m = 6.0;   // walls at y = +-half_width_y_m [m]
  double height_m = 4.0;         // ceiling at z = height_m [m]
  int landmarks = 6000;          // spread uniformly over the six faces
};

struct SimulatorOptions {
  uint32_t seed = 1;
  int64_t start_time_ns = 1600000000000000000;  // first IMU stamp [ns]
  double duration_s = 40.0;    // IMU and ground truth span [s], still included
  double gravity_m_s2 = 9.81;  // g [m/s^2]
  SimMotionOptions motion;
  SimImuOptions imu;
  SimCameraOptions camera;
  SimRoomOptions room;

  // True when every field is in range (duration_s in (0, 600], start_time_ns
  // in [0, 2^62]) and the trajectory stays at least
  // 0.5 m inside the room; otherwise false with a message that starts with the
  // offending field's name (sections as in the YAML: "camera.outlier_...").
  bool Validate(std::string* message) const;
};

struct SimulationSummary {
  double duration_s = 0.0;  // IMU span [s]
  int64_t imu_samples = 0;
  int64_t frames = 0;        // camera frames (stereo pairs count 1)
  int64_t observations = 0;  // all cameras
  int64_t outliers = 0;
  double mean_cam0_observations = 0.0;  // per frame
  int max_cam0_observations = 0;        // per frame
  int64_t tracks = 0;                   // distinct feature ids
  double mean_track_length = 0.0;       // cam0 frames per track
};

struct Simulation {
  SimulatorOptions options;
  std::vector<ImuSample> imu;       // measured, as written to imu0/data.csv
  std::vector<ImuSample> imu_true;  // exact: no bias, no noise
  // At every IMU stamp: pose, velocity and the biases in effect.
  std::vector<StampedState> ground_truth;
  std::vector<Eigen::Vector3d> landmarks_w;  // [m]
  // landmark_of_feature[feature_id]: the landmark a track follows.
  std::vector<int> landmark_of_feature;
  // Camera frames (camera stamps); uv only; cam0's observations first.
  std::vector<FeatureFrame> frames;
  // is_outlier[i][j]: frames[i].observations[j] is an outlier.
  std::vector<std::vector<bool>> is_outlier;
  SimulationSummary summary;
};

// Runs the simulation in memory. Throws std::invalid_argument with
// Validate()'s message when the options are invalid.
Simulation Simulate(const SimulatorOptions& options);

// What a simulation may take from elsewhere (a recorded flight, see
// dataset/flight_simulation.h) instead of making it from the options. Null
// members are made as Simulate(options) makes them. Not owned.
struct SimulationInputs {
  // The motion: t seconds after options.start_time_ns; it must cover
  // [0, options.duration_s]. Null: SimTrajectory(options.motion).
  const TrajectorySource* trajectory = nullptr;
  // A recorded IMU, passed through unchanged (the samples within the span
  // [start_time_ns, start_time_ns + duration_s]); the ground truth is then
  // at its stamps, with zero biases (the recording's are unknown here).
  // Null: synthesised from the trajectory with options.imu.
  const std::vector<ImuSample>* recorded_imu = nullptr;
  // The landmarks [m]. Null: the room of options.room.
  const std::vector<Eigen::Vector3d>* landmarks_w = nullptr;
  // Camera stamps [ns] (increasing), used where their exposure lies in the
  // span. Null: from start_time_ns at cam0's rate.
  const std::vector<int64_t>* frame_stamps_ns = nullptr;
};

// The same with some parts supplied. Throws std::invalid_argument for invalid
// options, an empty recorded IMU span, no landmarks or unordered stamps.
Simulation Simulate(const SimulatorOptions& options,
                    const SimulationInputs& inputs);

}  // namespace vio

#endif  // VIO_DATASET_SIMULATOR_H_
