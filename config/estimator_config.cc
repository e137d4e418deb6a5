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
  const std::string backend = n.Get<std::string>("backend");
  if (Upper(backend) == "WINDOW") {
    o->backend = SolverBackend::kWindow;
  } else if (Upper(backend) == "CERES") {
    o->backend = SolverBackend::kCeres;
  } else {
    throw ConfigError(n.Where("backend") + " must be window or ceres (got '" +
                      backend + "')");
  }
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
  o->function_tolerance = n.Get<double>("function_tolerance");
  o->max_time_s = n.Get<double>("max_time_s");
  o->num_threads = n.Get<int>("num_threads");
  o->kept_factor_pcg = n.Get<bool>("kept_factor_pcg");
}

void ReadInit(const YamlNode& n, InitOptions* o) {
  const std::string method = n.Get<std::string>("method");
  if (!ParseInitMethod(method, &o->method)) {
    throw ConfigError(n.Where("method") +
                      " must be one of auto, static, mono, stereo (got '" +
                      method + "')");
  }
  o->reinitialize_after_reset = n.Get<bool>("reinitialize_after_reset");
  o->max_rotation_misfit_deg = n.Get<double>("max_rotation_misfit_deg");
  o->max_gravity_error = n.Get<double>("max_gravity_error");
  o->max_speed_m_s = n.Get<double>("max_speed_m_s");
  o->refine_iterations = n.Get<int>("refine_iterations");
  o->max_refine_scale_change = n.Get<double>("max_refine_scale_change");
  o->refine_tilt_rad = n.Get<double>("refine_tilt_rad");
  const YamlNode m = n.Child("mono");
  o->mono.window_s = m.Get<double>("window_s");
  o->mono.max_frames = m.Get<int>("max_frames");
  o->mono.min_span_s = m.Get<double>("min_span_s");
  o->mono.min_parallax_px = m.Get<double>("min_parallax_px");
  o->mono.min_correspondences = m.Get<int>("min_correspondences");
  o->mono.min_inliers = m.Get<int>("min_inliers");
  o->mono.ransac_threshold_px = m.Get<double>("ransac_threshold_px");
  o->mono.min_pnp_inliers = m.Get<int>("min_pnp_inliers");
  o->mono.pnp_threshold_px = m.Get<double>("pnp_threshold_px");
  o->mono.max_reprojection_rms_px = m.Get<double>("max_reprojection_rms_px");
  o->mono.bundle_iterations = m.Get<int>("bundle_iterations");
  o->mono.outlier_threshold_px = m.Get<double>("outlier_threshold_px");
  o->mono.outlier_rounds = m.Get<int>("outlier_rounds");
  o->mono.max_outlier_share = m.Get<double>("max_outlier_share");
  o->mono.refine_outlier_rounds = m.Get<int>("refine_outlier_rounds");
  o->mono.min_imu_excitation = m.Get<double>("min_imu_excitation");
  o->mono.max_scale_uncertainty = m.Get<double>("max_scale_uncertainty");
  o->mono.long_window_s = m.Get<double>("long_window_s");
  o->mono.max_refined_scale_uncertainty =
      m.Get<double>("max_refined_scale_uncertainty");
  o->mono.gyro_aided = m.Get<bool>("gyro_aided");
  o->mono.gyro_min_tracks = m.Get<int>("gyro_min_tracks");
  o->mono.gyro_min_parallax_px = m.Get<double>("gyro_min_parallax_px");
  o->mono.gyro_max_refine_change_sigmas =
      m.Get<double>("gyro_max_refine_change_sigmas");
  o->mono.realign_after_s = m.Get<double>("realign_after_s");
  o->mono.realign_window_s = m.Get<double>("realign_window_s");
  o->mono.realign_max_scale_uncertainty =
      m.Get<double>("realign_max_scale_uncertainty");
  o->mono.realign_min_change = m.Get<double>("realign_min_change");
  const YamlNode s = n.Child("stereo");
  o->stereo.window_s = s.Get<double>("window_s");
  o->stereo.min_span_s = s.Get<double>("min_span_s");
  o->stereo.min_stereo_points = s.Get<int>("min_stereo_points");
  o->stereo.min_pnp_inliers = s.Get<int>("min_pnp_inliers");
  o->stereo.pnp_threshold_px = s.Get<double>("pnp_threshold_px");
  o->stereo.refine_outlier_rounds = s.Get<int>("refine_outlier_rounds");
  o->stereo.refine_outlier_threshold_px =
      s.Get<double>("refine_outlier_threshold_px");
  o->stereo.refine_prescreen_threshold_px =
      s.Get<double>("refine_prescreen_threshold_px");
  o->stereo.max_refine_scale_change =
      s.Get<double>("max_refine_scale_change");
}

void ReadZeroVelocity(const YamlNode& z, ZeroVelocityOptions* o) {
  o->enabled = z.Get<bool>("enabled");
  o->imu_window_s = z.Get<double>("imu_window_s");
  o->block_s = z.Get<double>("block_s");
  o->max_acc_std = z.Get<double>("max_acc_std");
  o->max_gyr_std = z.Get<double>("max_gyr_std");
  o->image_span_s = z.Get<double>("image_span_s");
  o->max_disparity_px = z.Get<double>("max_disparity_px");
  o->min_common_features = z.Get<int>("min_common_features");
  o->max_speed_without_image_m_s = z.Get<double>("max_speed_without_image_m_s");
  o->sigma_position_m = z.Get<double>("sigma_position_m");
  o->sigma_rotation_rad = z.Get<double>("sigma_rotation_rad");
  o->sigma_velocity_m_s = z.Get<double>("sigma_velocity_m_s");
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
  const std::string reanchored = l.Get<std::string>("reanchored_tracks");
  if (!ParseReanchoredTracks(reanchored, &o->landmarks.reanchored_tracks)) {
    throw ConfigError(l.Where("reanchored_tracks") +
                      " must be one of reuse, keep_point, keep_point_fej "
                      "(got '" +
                      reanchored + "')");
  }
  o->landmarks.world_points_in_max_landmarks =
      l.Get<bool>("world_points_in_max_landmarks");
  o->landmarks.max_world_points = l.Get<int>("max_world_points");
  o->landmarks.reuse_after_moving_start_s =
      l.Get<double>("reuse_after_moving_start_s");
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
  ReadInit(e.Child("init"), &o->init);
  ReadZeroVelocity(e.Child("zero_velocity"), &o->zero_velocity);
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
      << " px, at most " << o.landmarks.max_landmarks
      << ", re-anchored tracks: "
      << ReanchoredTracksName(o.landmarks.reanchored_tracks)
      << (o.landmarks.world_points_in_max_landmarks
              ? ""
              : " (world points on top of the maximum)")
      << (o.landmarks.max_world_points > 0
              ? ", world points at most " +
                    std::to_string(o.landmarks.max_world_points)
              : std::string())
      << "\n"
      << "  solver: "
      << (o.solver.backend == SolverBackend::kWindow
              ? std::string("window (inverse depths eliminated)")
              : std::string("ceres ") +
                    ceres::LinearSolverTypeToString(o.solver.linear_solver))
      << ", " << ceres::TrustRegionStrategyTypeToString(o.solver.trust_region)
      << ", <= " << o.solver.max_iterations
      << " iterations, function tolerance " << o.solver.function_tolerance
      << ", "
      << (o.solver.max_time_s > 0.0
              ? "<= " + std::to_string(o.solver.max_time_s) + " s (real time), "
              : std::string("no time limit, "))
      << o.solver.num_threads << " thread(s)"
      << (o.solver.kept_factor_pcg
              ? ", later linearisations by PCG on the kept factor"
              : std::string())
      << "\n"
      << "  start: " << InitMethodName(o.init.method)
      << (o.init.method == InitMethod::kAuto
              ? std::string(" (static, then ") +
                    (o.use_stereo ? "stereo" : "mono") + " in motion)"
              : std::string())
      << ", re-start after a reset "
      << (o.init.reinitialize_after_reset ? "on" : "off") << "; zero velocity "
      << (o.zero_velocity.enabled ? "on" : "off") << "\n"
      << "  imu stream: " << o.imu_stream.rate_hz << " Hz, range +-"
      << o.imu_stream.range.accelerometer_range << " m/s^2, +-"
      << o.imu_stream.range.gyroscope_range << " rad/s; speed limit "
      << o.failure.max_speed_m_s << " m/s\n";
  return out.str();
}

}  // namespace vio
