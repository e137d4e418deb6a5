#include "dataset/flight_simulation.h"

#include <algorithm>
#include <optional>
#include <random>
#include <stdexcept>

namespace vio {
namespace {

// The ground truth's samples within [first_ns, last_ns], as poses.
std::vector<StampedPose> PosesWithin(const std::vector<StampedState>& states,
                                     int64_t first_ns, int64_t last_ns) {
  std::vector<StampedPose> poses;
  for (const StampedState& s : states) {
    if (s.t_ns >= first_ns && s.t_ns <= last_ns) poses.push_back(PoseOf(s));
  }
  return poses;
}

// The recorded stamps within the span, continued at `period_ns` before the
// first and after the last one (a recording whose images stop early, as the
// V1_01 excerpt's). *recorded counts the stamps taken from the recording.
std::vector<int64_t> FrameStamps(const std::vector<int64_t>& recorded_ns,
                                 int64_t first_ns, int64_t last_ns,
                                 int64_t period_ns, int64_t* recorded) {
  std::vector<int64_t> stamps;
  *recorded = 0;
  for (int64_t t : recorded_ns) {
    if (t < first_ns || t > last_ns) continue;
    if (!stamps.empty() && t <= stamps.back()) {
      throw std::invalid_argument("flight: frame stamps must increase");
    }
    stamps.push_back(t);
  }
  *recorded = static_cast<int64_t>(stamps.size());
  if (stamps.empty()) stamps.push_back(first_ns);
  std::vector<int64_t> before;
  for (int64_t t = stamps.front() - period_ns; t >= first_ns; t -= period_ns) {
    before.push_back(t);
  }
  stamps.insert(stamps.begin(), before.rbegin(), before.rend());
  for (int64_t t = stamps.back() + period_ns; t <= last_ns; t += period_ns) {
    stamps.push_back(t);
  }
  return stamps;
}

// b_a, b_g of the recorded ground truth at t_ns, linearly interpolated (held
// at the ends).
void InterpolateBiases(const std::vector<StampedState>& states,
                       StampedState* truth) {
  const auto after = std::lower_bound(
      states.begin(), states.end(), truth->t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  if (after == states.begin() || after == states.end()) {
    const StampedState& s = after == states.end() ? states.back() : *after;
    truth->b_a = s.b_a;
    truth->b_g = s.b_g;
    return;
  }
  const StampedState& a = *(after - 1);
  const double u = static_cast<double>(truth->t_ns - a.t_ns) /
                   static_cast<double>(after->t_ns - a.t_ns);
  truth->b_a = (1.0 - u) * a.b_a + u * after->b_a;
  truth->b_g = (1.0 - u) * a.b_g + u * after->b_g;
}

SimulatorOptions FlightSimulatorOptions(const SimulatorOptions& preset,
                                        const FlightOptions& options,
                                        const RecordedFlight& flight,
                                        const TrajectoryCurve& curve) {
  SimulatorOptions o = preset;
  o.start_time_ns = curve.start_ns();
  o.duration_s = curve.duration_s();
  if (!flight.cameras.empty()) {
    o.camera.cam0 = flight.cameras[0];
    if (flight.cameras.size() > 1) {
      o.camera.cam1 = flight.cameras[1];
    } else if (o.camera.stereo) {
      throw std::invalid_argument(flight.folder +
                                  ": stereo needs cam1/sensor.yaml beside "
                                  "cam0's (or neither, for EuRoC's built-in "
                                  "calibration)");
    }
  }
  if (options.imu == FlightImu::kRecorded && flight.has_imu_noise) {
    o.imu.noise = flight.imu_noise;
  }
  return o;
}

}  // namespace

bool FlightOptions::Validate(std::string* message) const {
  std::string m;
  if (!curve.Validate(&m)) {
    *message = "curve." + m;
    return false;
  }
  if (!imu_curve.Validate(&m)) {
    *message = "imu_curve." + m;
    return false;
  }
  if (fit == FlightCurve::kGroundTruthAndImu && imu != FlightImu::kRecorded) {
    *message = "the curve fitted to the IMU needs the recorded IMU";
    return false;
  }
  if (!room.Validate(&m)) {
    *message = "room." + m;
    return false;
  }
  return true;
}

FlightSimulation SimulateFlight(const SimulatorOptions& preset,
                                const FlightOptions& options,
                                const RecordedFlight& flight) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("flight options: " + message);
  }
  if (flight.ground_truth.size() < 2) {
    throw std::invalid_argument(flight.folder + ": no ground truth to follow");
  }
  const bool recorded = options.imu == FlightImu::kRecorded;
  int64_t first_ns = flight.ground_truth.front().t_ns;
  int64_t last_ns = flight.ground_truth.back().t_ns;
  if (recorded) {
    if (flight.imu.empty()) {
      throw std::invalid_argument(flight.folder +
                                  ": no IMU recording (mav0/imu0/data.csv); "
                                  "use the synthetic IMU");
    }
    first_ns = std::max(first_ns, flight.imu.front().t_ns);
    last_ns = std::min(last_ns, flight.imu.back().t_ns);
  }
  const std::vector<StampedPose> poses =
      PosesWithin(flight.ground_truth, first_ns, last_ns);
  if (poses.size() < 2) {
    throw std::invalid_argument(flight.folder +
                                ": the IMU recording and the ground truth "
                                "do not overlap");
  }
  FlightSimulation out;
  std::optional<ImuCurveFit> joint;
  if (options.fit == FlightCurve::kGroundTruthAndImu) {
    ImuCurveFitOptions fit = options.imu_curve;
    fit.gravity_m_s2 = preset.gravity_m_s2;  // the simulation's own g
    joint.emplace(FitCurveToImu(
        poses, flight.imu, flight.has_imu_noise ? flight.imu_noise : ImuNoise(),
        fit));
    out.imu_fitted = true;
    out.imu_fit = joint->report;
  }
  out.followed =
      joint.has_value()
          ? std::make_shared<const TrajectoryCurve>(joint->curve)
          : std::make_shared<const TrajectoryCurve>(poses, options.curve);
  const TrajectoryCurve& curve = *out.followed;
  out.curve = curve.report();
  out.cameras_from_folder = !flight.cameras.empty();
  const SimulatorOptions o =
      FlightSimulatorOptions(preset, options, flight, curve);

  std::vector<Eigen::Vector3d> path;
  for (double t = 0.0; t <= curve.duration_s(); t += 0.01) {
    const Eigen::Vector3d p = curve.At(t).p_w_b;
    if (!path.empty()) out.path_length_m += (p - path.back()).norm();
    path.push_back(p);
  }
  std::seed_seq room_seed{o.seed, 7u};
  std::mt19937 rng(room_seed);
  out.room = MakeFlightRoom(path, options.room, &rng);

  const int64_t period_ns = std::llround(1e9 / o.camera.cam0.rate_hz);
  const int64_t t_d_ns = std::llround(o.camera.time_offset_s * 1e9);
  const std::vector<int64_t> stamps =
      FrameStamps(flight.frame_stamps_ns, curve.start_ns() - t_d_ns,
                  curve.end_ns() - t_d_ns, period_ns, &out.recorded_frames);
  SimulationInputs inputs;
  inputs.trajectory = &curve;
  inputs.recorded_imu = recorded ? &flight.imu : nullptr;
  inputs.landmarks_w = &out.room.landmarks_w;
  inputs.frame_stamps_ns = &stamps;
  out.simulation = Simulate(o, inputs);
  out.room.landmarks_w.clear();
  if (joint.has_value()) {
    for (StampedState& truth : out.simulation.ground_truth) {
      truth.b_g = joint->GyroBiasAt(truth.t_ns);
      truth.b_a = joint->AccelBiasAt(truth.t_ns);
    }
  } else if (recorded && flight.has_biases) {
    for (StampedState& truth : out.simulation.ground_truth) {
      InterpolateBiases(flight.ground_truth, &truth);
    }
  }
  return out;
}

}  // namespace vio
