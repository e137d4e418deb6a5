#include "config/estimator_config.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace vio {
namespace {

std::string ConfigPath(const std::string& name) {
  return std::string(VIO_SOURCE_DIR) + "/config/" + name;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the ConfigError that loading `text` raises ("" if none).
std::string ErrorOf(const std::string& text) {
  try {
    ReadEstimatorOptions(YamlNode::LoadString(text, "test.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from,
                    const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(EstimatorConfig, DefaultYamlEqualsTheBuiltInDefaults) {
  const EstimatorOptions o =
      ReadEstimatorOptions(YamlNode::LoadFile(ConfigPath("default.yaml")));
  const EstimatorOptions d;
  EXPECT_EQ(o.window_size, d.window_size);
  EXPECT_EQ(o.use_stereo, false);
  EXPECT_EQ(o.keyframe.min_parallax_px, d.keyframe.min_parallax_px);
  EXPECT_EQ(o.keyframe.min_tracked_features, d.keyframe.min_tracked_features);
  EXPECT_EQ(o.triangulation.min_parallax_deg, d.triangulation.min_parallax_deg);
  EXPECT_EQ(o.triangulation.max_depth_m, d.triangulation.max_depth_m);
  EXPECT_EQ(o.landmarks.outlier_threshold_px, d.landmarks.outlier_threshold_px);
  EXPECT_EQ(o.landmarks.max_landmarks, d.landmarks.max_landmarks);
  EXPECT_EQ(o.landmarks.reanchored_tracks, d.landmarks.reanchored_tracks);
  EXPECT_EQ(o.landmarks.world_points_in_max_landmarks,
            d.landmarks.world_points_in_max_landmarks);
  EXPECT_EQ(o.landmarks.max_world_points, d.landmarks.max_world_points);
  EXPECT_EQ(o.landmarks.reuse_after_moving_start_s,
            d.landmarks.reuse_after_moving_start_s);
  EXPECT_EQ(o.static_init.max_acc_std, d.static_init.max_acc_std);
  EXPECT_EQ(o.state_prior.tilt_rad, d.state_prior.tilt_rad);
  EXPECT_EQ(o.failure.max_position_jump_m, d.failure.max_position_jump_m);
  EXPECT_EQ(o.failure.max_speed_m_s, d.failure.max_speed_m_s);
  EXPECT_EQ(o.solver.backend, d.solver.backend);
  EXPECT_EQ(o.solver.linear_solver, d.solver.linear_solver);
  EXPECT_EQ(o.solver.trust_region, d.solver.trust_region);
  EXPECT_EQ(o.solver.max_iterations, d.solver.max_iterations);
  EXPECT_EQ(o.solver.function_tolerance, d.solver.function_tolerance);
  EXPECT_EQ(o.solver.num_threads, 1);
  EXPECT_EQ(o.solver.kept_factor_pcg, d.solver.kept_factor_pcg);
  EXPECT_EQ(o.init.method, d.init.method);
  EXPECT_EQ(o.init.reinitialize_after_reset, d.init.reinitialize_after_reset);
  EXPECT_EQ(o.init.max_rotation_misfit_deg, d.init.max_rotation_misfit_deg);
  EXPECT_EQ(o.init.max_gravity_error, d.init.max_gravity_error);
  EXPECT_EQ(o.init.max_speed_m_s, d.init.max_speed_m_s);
  EXPECT_EQ(o.init.refine_iterations, d.init.refine_iterations);
  EXPECT_EQ(o.init.max_refine_scale_change, d.init.max_refine_scale_change);
  EXPECT_EQ(o.init.refine_tilt_rad, d.init.refine_tilt_rad);
  EXPECT_EQ(o.init.mono.window_s, d.init.mono.window_s);
  EXPECT_EQ(o.init.mono.max_frames, d.init.mono.max_frames);
  EXPECT_EQ(o.init.mono.min_span_s, d.init.mono.min_span_s);
  EXPECT_EQ(o.init.mono.min_parallax_px, d.init.mono.min_parallax_px);
  EXPECT_EQ(o.init.mono.min_correspondences, d.init.mono.min_correspondences);
  EXPECT_EQ(o.init.mono.min_inliers, d.init.mono.min_inliers);
  EXPECT_EQ(o.init.mono.ransac_threshold_px, d.init.mono.ransac_threshold_px);
  EXPECT_EQ(o.init.mono.min_pnp_inliers, d.init.mono.min_pnp_inliers);
  EXPECT_EQ(o.init.mono.pnp_threshold_px, d.init.mono.pnp_threshold_px);
  EXPECT_EQ(o.init.mono.max_reprojection_rms_px,
            d.init.mono.max_reprojection_rms_px);
  EXPECT_EQ(o.init.mono.bundle_iterations, d.init.mono.bundle_iterations);
  EXPECT_EQ(o.init.mono.outlier_threshold_px, d.init.mono.outlier_threshold_px);
  EXPECT_EQ(o.init.mono.outlier_rounds, d.init.mono.outlier_rounds);
  EXPECT_EQ(o.init.mono.max_outlier_share, d.init.mono.max_outlier_share);
  EXPECT_EQ(o.init.mono.refine_outlier_rounds,
            d.init.mono.refine_outlier_rounds);
  EXPECT_EQ(o.init.mono.min_imu_excitation, d.init.mono.min_imu_excitation);
  EXPECT_EQ(o.init.mono.max_scale_uncertainty,
            d.init.mono.max_scale_uncertainty);
  EXPECT_EQ(o.init.mono.long_window_s, d.init.mono.long_window_s);
  EXPECT_EQ(o.init.mono.max_refined_scale_uncertainty,
            d.init.mono.max_refined_scale_uncertainty);
  EXPECT_EQ(o.init.mono.gyro_aided, d.init.mono.gyro_aided);
  EXPECT_EQ(o.init.mono.gyro_min_tracks, d.init.mono.gyro_min_tracks);
  EXPECT_EQ(o.init.mono.gyro_min_parallax_px, d.init.mono.gyro_min_parallax_px);
  EXPECT_EQ(o.init.mono.gyro_max_refine_change_sigmas,
            d.init.mono.gyro_max_refine_change_sigmas);
  EXPECT_EQ(o.init.mono.realign_after_s, d.init.mono.realign_after_s);
  EXPECT_EQ(o.init.mono.realign_window_s, d.init.mono.realign_window_s);
  EXPECT_EQ(o.init.mono.realign_max_scale_uncertainty,
            d.init.mono.realign_max_scale_uncertainty);
  EXPECT_EQ(o.init.mono.realign_min_change, d.init.mono.realign_min_change);
  EXPECT_EQ(o.init.stereo.window_s, d.init.stereo.window_s);
  EXPECT_EQ(o.init.stereo.min_span_s, d.init.stereo.min_span_s);
  EXPECT_EQ(o.init.stereo.min_stereo_points, d.init.stereo.min_stereo_points);
  EXPECT_EQ(o.init.stereo.min_pnp_inliers, d.init.stereo.min_pnp_inliers);
  EXPECT_EQ(o.init.stereo.pnp_threshold_px, d.init.stereo.pnp_threshold_px);
  EXPECT_EQ(o.init.stereo.refine_outlier_rounds,
            d.init.stereo.refine_outlier_rounds);
  EXPECT_EQ(o.init.stereo.refine_outlier_threshold_px,
            d.init.stereo.refine_outlier_threshold_px);
  EXPECT_EQ(o.init.stereo.refine_prescreen_threshold_px,
            d.init.stereo.refine_prescreen_threshold_px);
  EXPECT_EQ(o.init.stereo.max_refine_scale_change,
            d.init.stereo.max_refine_scale_change);
  const ZeroVelocityOptions& z = o.zero_velocity;
  const ZeroVelocityOptions& dz = d.zero_velocity;
  EXPECT_EQ(z.enabled, dz.enabled);
  EXPECT_EQ(z.imu_window_s, dz.imu_window_s);
  EXPECT_EQ(z.block_s, dz.block_s);
  EXPECT_EQ(z.max_acc_std, dz.max_acc_std);
  EXPECT_EQ(z.max_gyr_std, dz.max_gyr_std);
  EXPECT_EQ(z.image_span_s, dz.image_span_s);
  EXPECT_EQ(z.max_disparity_px, dz.max_disparity_px);
  EXPECT_EQ(z.min_common_features, dz.min_common_features);
  EXPECT_EQ(z.max_speed_without_image_m_s, dz.max_speed_without_image_m_s);
  EXPECT_EQ(z.sigma_position_m, dz.sigma_position_m);
  EXPECT_EQ(z.sigma_rotation_rad, dz.sigma_rotation_rad);
  EXPECT_EQ(z.sigma_velocity_m_s, dz.sigma_velocity_m_s);
}

TEST(EstimatorConfig, EveryPresetHasTheStartAndZeroVelocityBlocks) {
  for (const char* name : {"default.yaml", "stereo.yaml", "euroc_mono.yaml",
                           "euroc_stereo.yaml"}) {
    SCOPED_TRACE(name);
    const EstimatorOptions o =
        ReadEstimatorOptions(YamlNode::LoadFile(ConfigPath(name)));
    EXPECT_EQ(o.init.method, InitMethod::kAuto);
    EXPECT_TRUE(o.zero_velocity.enabled);
  }
}

TEST(EstimatorConfig, StereoPresetTurnsStereoOn) {
  const EstimatorOptions o =
      ReadEstimatorOptions(YamlNode::LoadFile(ConfigPath("stereo.yaml")));
  EXPECT_TRUE(o.use_stereo);
  EXPECT_EQ(o.window_size, 10);
}

TEST(EstimatorConfig, ErrorsNameFileAndKey) {
  const std::string text = ReadText(ConfigPath("default.yaml"));
  EXPECT_EQ(ErrorOf(Replace(text, "window_size: 10", "window_size: 1")),
            "test.yaml: estimator.window_size must be >= 2 (got 1)");
  EXPECT_EQ(ErrorOf(Replace(text, "    max_landmarks: 120", "")),
            "test.yaml: estimator.landmarks.max_landmarks is missing");
  EXPECT_EQ(ErrorOf(Replace(text, "    world_points_in_max_landmarks: false",
                            "")),
            "test.yaml: estimator.landmarks.world_points_in_max_landmarks is "
            "missing");
  EXPECT_EQ(ErrorOf(Replace(text, "    max_world_points: 50", "")),
            "test.yaml: estimator.landmarks.max_world_points is missing");
  EXPECT_EQ(ErrorOf(Replace(text, "    max_world_points: 50 ",
                            "    max_world_points: -1 ")),
            "test.yaml: estimator.landmarks.max_world_points must be >= 0 "
            "(got -1)");
  EXPECT_EQ(ErrorOf(Replace(text, "    reuse_after_moving_start_s: 4 ", "")),
            "test.yaml: estimator.landmarks.reuse_after_moving_start_s is "
            "missing");
  EXPECT_EQ(ErrorOf(Replace(text, "reuse_after_moving_start_s: 4 ",
                            "reuse_after_moving_start_s: -1 ")),
            "test.yaml: estimator.landmarks.reuse_after_moving_start_s must "
            "be >= 0 (got -1)");
  EXPECT_EQ(ErrorOf(Replace(text, "linear_solver: dense_schur",
                            "linear_solver: cholmod")),
            "test.yaml: estimator.solver.linear_solver must be a Ceres "
            "linear solver such as dense_schur, sparse_schur, dense_qr (got "
            "'cholmod')");
  EXPECT_EQ(ErrorOf(Replace(text, "backend: window", "backend: fast")),
            "test.yaml: estimator.solver.backend must be window or ceres (got "
            "'fast')");
  EXPECT_EQ(ErrorOf(Replace(text, "function_tolerance: 1e-3",
                            "function_tolerance: 1.5")),
            "test.yaml: estimator.solver.function_tolerance must be in [0, 1) "
            "(got 1.5)");
  EXPECT_EQ(
      ReadEstimatorOptions(
          YamlNode::LoadString(
              Replace(text, "backend: window", "backend: Ceres"), "test.yaml"))
          .solver.backend,
      SolverBackend::kCeres);
  EXPECT_NE(ErrorOf(Replace(text, "min_depth_m: 0.1", "min_depth_m: x"))
                .find("estimator.triangulation.min_depth_m"),
            std::string::npos);
  EXPECT_EQ(ErrorOf("imu: {}\n"), "test.yaml: estimator is missing");
  EXPECT_EQ(ErrorOf(Replace(text, "method: auto", "method: dynamic")),
            "test.yaml: estimator.init.method must be one of auto, static, "
            "mono, stereo (got 'dynamic')");
  EXPECT_EQ(ErrorOf(Replace(text, "method: auto", "method: stereo")),
            "test.yaml: estimator.init.method stereo needs use_stereo: true");
  EXPECT_EQ(ErrorOf(Replace(text, "      max_frames: 11", "")),
            "test.yaml: estimator.init.mono.max_frames is missing");
  EXPECT_EQ(
      ErrorOf(Replace(text, "max_disparity_px: 3.0", "max_disparity_px: -3")),
      "test.yaml: estimator.zero_velocity.max_disparity_px must be > 0 "
      "(got -3)");
}

}  // namespace
}  // namespace vio
