#ifndef VIO_DATASET_FLIGHT_SIMULATION_H_
#define VIO_DATASET_FLIGHT_SIMULATION_H_

// A simulation along a recorded flight: the body follows the curve fitted to
// the flight's ground truth (dataset/trajectory_curve.h) through a room sized
// to the flight (dataset/flight_room.h), seen by the simulator's KLT-like
// tracker (dataset/sim_features.h) with the flight's camera calibration and
// frame stamps, and felt by either
//   - a synthetic IMU computed from the curve's derivatives, with the preset's
//     noise and bias random walk (the visual part alone is then what differs
//     from the model the estimator assumes: none), or
//   - the flight's recorded IMU, passed through unchanged (a real IMU: its
//     noise, vibration and bias drift are what they were).
// The span is the ground truth's (within the recorded IMU's, in that mode);
// the ground truth written is the curve at the IMU stamps, with the recorded
// biases (interpolated) when the ground truth has them, else zero in the
// recorded mode and the simulated ones in the synthetic mode.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dataset/flight_room.h"
#include "dataset/imu_curve_fit.h"
#include "dataset/simulator.h"
#include "dataset/trajectory.h"
#include "dataset/trajectory_curve.h"
#include "geometry/camera_model.h"
#include "preintegration/imu_types.h"

namespace vio {

// What a recorded sequence folder holds for a flight simulation (read by
// config/recorded_flight.h).
struct RecordedFlight {
  std::string folder;
  std::string ground_truth_path;
  std::vector<StampedState> ground_truth;  // poses; v and biases if known
  bool has_biases = false;                 // ground_truth's b_a, b_g are real
  std::vector<ImuSample> imu;              // empty: no IMU recording
  bool has_imu_noise = false;              // imu0/sensor.yaml was read
  ImuNoise imu_noise;
  // cam0 frame stamps (camN/data.csv or cam0_timestamps_only.csv) [ns]; may
  // be empty or cover only part of the flight.
  std::vector<int64_t> frame_stamps_ns;
  std::string frame_stamps_path;  // empty when none
  // camN/sensor.yaml calibrations (0, 1 or 2 of them).
  std::vector<CameraCalibration> cameras;
};

enum class FlightImu { kSynthetic, kRecorded };

// What the curve the body follows is fitted to: the ground truth alone
// (dataset/trajectory_curve.h), or the ground truth and the recorded IMU
// together (dataset/imu_curve_fit.h; recorded IMU only), so that the cameras
// move as the recorded IMU says.
enum class FlightCurve { kGroundTruth, kGroundTruthAndImu };

struct FlightOptions {
  FlightImu imu = FlightImu::kSynthetic;
  FlightCurve fit = FlightCurve::kGroundTruth;
  CurveFitOptions curve;         // kGroundTruth
  ImuCurveFitOptions imu_curve;  // kGroundTruthAndImu
  FlightRoomOptions room;

  bool Validate(std::string* message) const;
};

struct FlightSimulation {
  Simulation simulation;
  CurveFitReport curve;
  FlightRoom room;             // landmarks_w emptied (they are in simulation)
  double path_length_m = 0.0;  // of the curve over the span [m]
  bool cameras_from_folder = false;  // else EuRoC's built-in calibration
  int64_t recorded_frames = 0;  // frames at recorded stamps (rest: at rate)
  // kGroundTruthAndImu: how the joint fit went (curve holds its ground-truth
  // residuals too).
  bool imu_fitted = false;
  ImuCurveFitReport imu_fit;
  // The curve the body followed (for rendering images along it).
  std::shared_ptr<const TrajectoryCurve> followed;
};

// Simulates the flight with the preset's IMU noise, camera noise and track
// model (its motion, room and duration are not used; its seed is). Throws
// std::invalid_argument for invalid options, a flight with no ground truth,
// the recorded mode without an IMU recording, an IMU that does not overlap
// the ground truth, or the joint fit with the synthetic IMU. With the joint
// fit the ground truth written holds the fitted biases.
FlightSimulation SimulateFlight(const SimulatorOptions& preset,
                                const FlightOptions& options,
                                const RecordedFlight& flight);

}  // namespace vio

#endif  // VIO_DATASET_FLIGHT_SIMULATION_H_
