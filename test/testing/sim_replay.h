#ifndef VIO_TEST_TESTING_SIM_REPLAY_H_
#define VIO_TEST_TESTING_SIM_REPLAY_H_

// Runs the estimator on an in-memory simulation, as vio_replay does on a
// simulated folder (observation builder, then the sequence runner), and
// evaluates it against the simulator's truth (posyaw alignment).

#include <vector>

#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "frontend/observation_builder.h"

namespace vio {
namespace testing {

struct SimReplay {
  std::vector<EstimatorOutput> outputs;
  EstimatorSummary summary;
  double ate_rmse_m = -1.0;      // after posyaw alignment [m]
  double rpe_rmse_m = -1.0;      // over 1 m of travel [m]
  double final_b_a_error = 0.0;  // |b_a - truth| at the last frame [m/s^2]
  double final_b_g_error = 0.0;  // [rad/s]
  double time_offset_s = 0.0;    // the estimator's t_d at the end [s]
  Eigen::Isometry3d T_b_c0 = Eigen::Isometry3d::Identity();  // at the end
};

// A short simulation with a still start: `seconds` long, mono or stereo.
SimulatorOptions ShortSimulation(double seconds, bool stereo);

// config/sim_aggressive.yaml's motion (up to ~2.9 m/s, ~1.8 rad/s) and track
// drops after a 1 s still start, `seconds` long, mono or stereo, with the
// camera-IMU offset t_d [s].
SimulatorOptions AggressiveSimulation(double seconds, bool stereo, double t_d);

// The estimator options for a simulation (use_stereo as the simulation).
EstimatorOptions OptionsFor(const SimulatorOptions& simulation);

// The simulation's cameras and frames as the estimator takes them (xy and
// velocity from the observation builder).
struct PreparedSimulation {
  std::vector<EstimatorCamera> cameras;
  std::vector<FeatureFrame> frames;
  ObservationBuilderSummary removed;  // what the observation step removed
};
PreparedSimulation Prepare(const Simulation& simulation);
// The same for other frames (uv set) of the simulation's cameras, e.g. ones
// with faults injected.
PreparedSimulation Prepare(const Simulation& simulation,
                           std::vector<FeatureFrame> raw_frames);

// Runs the estimator over imu and frames and evaluates against the truth.
SimReplay Replay(const Simulation& simulation, const EstimatorOptions& options,
                 const std::vector<ImuSample>& imu,
                 const std::vector<FeatureFrame>& frames);

// Replay with the estimator given these cameras instead of the simulation's
// (e.g. a perturbed extrinsic to be estimated).
SimReplay ReplayWithCameras(const Simulation& simulation,
                            const EstimatorOptions& options,
                            const std::vector<EstimatorCamera>& cameras);

// ATE (and, with rpe_rmse_m, RPE over 1 m) of the initialised outputs from
// t_from_ns on against the simulation's truth, posyaw-aligned on those
// frames alone [m]: to compare two runs on the frames both estimate. False
// with fewer than three such outputs.
bool AteFrom(const Simulation& simulation,
             const std::vector<EstimatorOutput>& outputs, int64_t t_from_ns,
             double* ate_rmse_m, double* rpe_rmse_m = nullptr);

// Replay of the simulation as it is.
SimReplay ReplaySimulation(const Simulation& simulation,
                           const EstimatorOptions& options);

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_SIM_REPLAY_H_
