#include "test/testing/sim_replay.h"

#include <cstdint>
#include <utility>

#include "dataset/trajectory.h"
#include "estimator/sequence_runner.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "frontend/observation_builder.h"
#include "geometry/camera_model.h"

namespace vio {
namespace testing {

SimulatorOptions ShortSimulation(double seconds, bool stereo) {
  SimulatorOptions o;
  o.duration_s = seconds;
  o.camera.stereo = stereo;
  return o;
}

SimulatorOptions AggressiveSimulation(double seconds, bool stereo, double t_d) {
  SimulatorOptions o = ShortSimulation(seconds, stereo);
  o.motion.still_duration_s = 1.0;
  o.motion.blend_duration_s = 1.5;
  o.motion.lap_period_s = 7.0;
  o.motion.height_amplitude_m = 0.6;
  o.motion.roll_amplitude_rad = 0.35;
  o.motion.pitch_amplitude_rad = 0.35;
  o.motion.yaw_amplitude_rad = 0.6;
  o.camera.track_drop_probability = 0.06;
  o.camera.time_offset_s = t_d;
  return o;
}

EstimatorOptions OptionsFor(const SimulatorOptions& simulation) {
  EstimatorOptions o;
  o.use_stereo = simulation.camera.stereo;
  o.gravity_magnitude = simulation.gravity_m_s2;
  return o;
}

PreparedSimulation Prepare(const Simulation& simulation) {
  return Prepare(simulation, simulation.frames);
}

PreparedSimulation Prepare(const Simulation& simulation,
                           std::vector<FeatureFrame> raw_frames) {
  const SimCameraOptions& cam = simulation.options.camera;
  std::vector<CameraModel> models = {CameraModel(cam.cam0)};
  if (cam.stereo) models.push_back(CameraModel(cam.cam1));
  PreparedSimulation p;
  for (const CameraModel& m : models) {
    EstimatorCamera c;
    c.T_b_c.linear() = m.calibration().q_b_c.toRotationMatrix();
    c.T_b_c.translation() = m.calibration().t_b_c;
    c.focal_px = m.focal();
    p.cameras.push_back(c);
  }
  ObservationBuilder builder(models);
  p.frames = std::move(raw_frames);
  for (FeatureFrame& f : p.frames) builder.Process(&f);
  p.removed = builder.summary();
  return p;
}

SimReplay ReplaySimulation(const Simulation& simulation,
                           const EstimatorOptions& options) {
  return Replay(simulation, options, simulation.imu,
                Prepare(simulation).frames);
}

namespace {

SimReplay Run(const Simulation& simulation, const EstimatorOptions& options,
              const std::vector<EstimatorCamera>& cameras,
              const std::vector<ImuSample>& imu,
              const std::vector<FeatureFrame>& frames);

}  // namespace

bool AteFrom(const Simulation& simulation,
             const std::vector<EstimatorOutput>& outputs, int64_t t_from_ns,
             double* ate_rmse_m, double* rpe_rmse_m) {
  Trajectory estimate, truth;
  for (const EstimatorOutput& o : outputs) {
    if (o.processed && o.initialized && o.t_ns >= t_from_ns)
      estimate.push_back({o.t_ns, o.p_w_b, o.q_w_b});
  }
  for (const StampedState& s : simulation.ground_truth)
    truth.push_back(PoseOf(s));
  if (estimate.size() < 3) return false;
  const Association a = Associate(estimate, truth);
  const Alignment align =
      Align(a.estimate, a.ground_truth, AlignmentMode::kPosYaw);
  const Trajectory aligned = align.Apply(a.estimate);
  *ate_rmse_m = ComputeAte(aligned, a.ground_truth).translation.rmse;
  if (rpe_rmse_m != nullptr) {
    *rpe_rmse_m = ComputeRpe(aligned, a.ground_truth, 1.0, RpeUnit::kMeters)
                      .translation.rmse;
  }
  return true;
}

SimReplay ReplayWithCameras(const Simulation& simulation,
                            const EstimatorOptions& options,
                            const std::vector<EstimatorCamera>& cameras) {
  return Run(simulation, options, cameras, simulation.imu,
             Prepare(simulation).frames);
}

SimReplay Replay(const Simulation& simulation, const EstimatorOptions& options,
                 const std::vector<ImuSample>& imu,
                 const std::vector<FeatureFrame>& frames) {
  return Run(simulation, options, Prepare(simulation).cameras, imu, frames);
}

namespace {

SimReplay Run(const Simulation& simulation, const EstimatorOptions& options,
              const std::vector<EstimatorCamera>& cameras,
              const std::vector<ImuSample>& imu,
              const std::vector<FeatureFrame>& frames) {
  Estimator estimator(options, VisualFactorOptions(),
                      simulation.options.imu.noise, PreintegrationOptions(),
                      cameras);
  SimReplay r;
  r.outputs = RunSequence(&estimator, imu, frames);
  r.summary = estimator.summary();
  r.time_offset_s = estimator.time_offset_s();
  r.T_b_c0 = estimator.T_b_c(0);

  if (!AteFrom(simulation, r.outputs, INT64_MIN, &r.ate_rmse_m,
               &r.rpe_rmse_m)) {
    return r;
  }
  // Biases at the last estimate against the truth at that stamp.
  const EstimatorOutput& last = r.outputs.back();
  const StampedState* gt = &simulation.ground_truth.front();
  for (const StampedState& s : simulation.ground_truth) {
    if (s.t_ns <= last.t_ns) gt = &s;
  }
  r.final_b_a_error = (last.b_a - gt->b_a).norm();
  r.final_b_g_error = (last.b_g - gt->b_g).norm();
  return r;
}

}  // namespace

}  // namespace testing
}  // namespace vio
