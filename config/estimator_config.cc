#include "config/estimator_config.h"

#include <ceres/types.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>

namespace vio {
namespace {

std::string Upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  return s;
}

void ReadSolver(const YamlNode& n, SolverOptions* o) {
  const std::string linear = n.Get<std::string>("linear_solver");
  if (!ceres::StringToLinearSolverType(Upper(linear), &o->linear_solver)) {
    throw ConfigError(n.Where("linear_solver") +
                      " must be a Ceres linear solver such as dense_schur, "
                      "sparse_schur, dense_qr (got '" +
                      linear + "')");
  }
  const std::string region = n.Get<std::string>("trust_region");
  if (!ceres::StringToTrustRegionStrategyType(Upper(region),
                                              &o->trust_region)) {
    throw ConfigError(n.Where("trust_region") +
                      " must be dogleg or levenberg_marquardt (got '" + region +
                      "')");
  }
  o->max_iterations = n.Get<int>("max_iterations");
  o->max_time_s = n.Get<double>("max_time_s");
  o->num_threads = n.Get<int>("num_threads");
}

void ReadSections(const YamlNode& e, EstimatorOptions* o) {
  const YamlNode k = e.Child("keyframe");
  o->keyframe.min_parallax_px = k.Get<double>("min_parallax_px");
  o->keyframe.min_tracked_features = k.Get<int>("min_tracked_features");
  const YamlNode t = e.Child("triangulation");
  o->triangulation.min_parallax_deg = t.Get<double>("min_parallax_deg");
  o->triangulation.min_depth_m = t.Get<double>("min_depth_m");
  o->triangulation.max_depth_m = t.Get<double>("max_depth_m");
  o->triangulation.min_observations = t.Get<int>("min_observations");
  const YamlNode l = e.Child("landmarks");
  o->landmarks.outlier_threshold_px = l.Get<double>("outlier_threshold_px");
  o->landmarks.max_landmarks = l.Get<int>("max_landmarks");
  const YamlNode s = e.Child("static_init");
  o->static_init.window_s = s.Get<double>("window_s");
  o->static_init.block_s = s.Get<double>("block_s");
  o->static_init.max_acc_std = s.Get<double>("max_acc_std");
  o->static_init.max_gyr_std = s.Get<double>("max_gyr_std");
  o->static_init.estimate_accel_bias = s.Get<bool>("estimate_accel_bias");
  const YamlNode p = e.Child("state_prior");
  o->state_prior.position_m = p.Get<double>("position_m");
  o->state_prior.yaw_rad = p.Get<double>("yaw_rad");
  o->state_prior.tilt_rad = p.Get<double>("tilt_rad");
  o->state_prior.velocity_still = p.Get<double>("velocity_still");
  o->state_prior.velocity_moving = p.Get<double>("velocity_moving");
  o->state_prior.accel_bias = p.Get<double>("accel_bias");
  o->state_prior.gyro_bias = p.Get<double>("gyro_bias");
  o->state_prior.extrinsic_rotation_rad =
      p.Get<double>("extrinsic_rotation_rad");
  o->state_prior.extrinsic_translation_m =
      p.Get<double>("extrinsic_translation_m");
  const YamlNode f = e.Child("failure");
  o->failure.min_tracked_landmarks = f.Get<int>("min_tracked_landmarks");
  o->failure.max_accel_bias = f.Get<double>("max_accel_bias");
  o->failure.max_gyro_bias = f.Get<double>("max_gyro_bias");
  o->failure.max_position_jump_m = f.Get<double>("max_position_jump_m");
  o->failure.max_rotation_jump_deg = f.Get<double>("max_rotation_jump_deg");
  o->failure.max_speed_m_s = f.Get<double>("max_speed_m_s");
  ReadSolver(e.Child("solver"), &o->solver);
}

}  // namespace

EstimatorOptions ReadEstimatorOptions(const YamlNode& root) {
  const YamlNode e = root.Child("estimator");
  EstimatorOptions o;
  o.window_size = e.Get<int>("window_size");
  o.use_stereo = e.Get<bool>("use_stereo");
  o.estimate_extrinsics = e.Get<bool>("estimate_extrinsics");
  o.estimate_time_offset = e.Get<bool>("estimate_time_offset");
  o.initial_time_offset_s = e.Get<double>("initial_time_offset_s");
  ReadSections(e, &o);
  ValidateAt(e, o);
  return o;
}

std::string DescribeEstimatorOptions(const EstimatorOptions& o) {
  std::ostringstream out;
  out << "estimator: window_size " << o.window_size << ", "
      << (o.use_stereo ? "stereo" : "mono") << ", extrinsics "
      << (o.estimate_extrinsics ? "estimated" : "fixed") << ", time offset "
      << (o.estimate_time_offset ? "estimated" : "fixed") << " (start "
      << o.initial_time_offset_s << " s)\n"
      << "  keyframe: parallax >= " << o.keyframe.min_parallax_px << " px or < "
      << o.keyframe.min_tracked_features << " tracked\n"
      << "  triangulation: parallax >= " << o.triangulation.min_parallax_deg
      << " deg, depth " << o.triangulation.min_depth_m << ".."
      << o.triangulation.max_depth_m << " m\n"
      << "  landmarks: outlier RMS > " << o.landmarks.outlier_threshold_px
      << " px, at most " << o.landmarks.max_landmarks << "\n"
      << "  solver: " << ceres::LinearSolverTypeToString(o.solver.linear_solver)
      << ", " << ceres::TrustRegionStrategyTypeToString(o.solver.trust_region)
      << ", <= " << o.solver.max_iterations << " iterations, "
      << (o.solver.max_time_s > 0.0
              ? "<= " + std::to_string(o.solver.max_time_s) + " s (real time), "
              : std::string("no time limit, "))
      << o.solver.num_threads << " thread(s)\n"
      << "  imu stream: " << o.imu_stream.rate_hz << " Hz, range +-"
      << o.imu_stream.range.accelerometer_range << " m/s^2, +-"
      << o.imu_stream.range.gyroscope_range << " rad/s; speed limit "
      << o.failure.max_speed_m_s << " m/s\n";
  return out.str();
}

}  // namespace vio
