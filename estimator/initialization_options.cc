#include "estimator/initialization_options.h"

#include <cmath>

#include "estimator/option_rules.h"

namespace vio {

const char* InitMethodName(InitMethod method) {
  switch (method) {
    case InitMethod::kAuto:
      return "auto";
    case InitMethod::kStatic:
      return "static";
    case InitMethod::kMono:
      return "mono";
    case InitMethod::kStereo:
      return "stereo";
    case InitMethod::kGyroAided:
      return "gyro-aided";
  }
  return "?";
}

bool ParseInitMethod(const std::string& name, InitMethod* method) {
  for (InitMethod m : {InitMethod::kAuto, InitMethod::kStatic,
                       InitMethod::kMono, InitMethod::kStereo}) {
    if (name == InitMethodName(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

bool InitOptions::Validate(bool stereo_available, int window_size,
                           std::string* message) const {
  if (method == InitMethod::kStereo && !stereo_available) {
    *message = "init.method stereo needs use_stereo: true";
    return false;
  }
  OptionRules r;
  r.Positive("init.mono.window_s", mono.window_s);
  r.Require(mono.long_window_s >= mono.window_s, "init.mono.long_window_s",
            mono.long_window_s, "must be >= init.mono.window_s");
  r.AtLeast("init.mono.max_frames", mono.max_frames, 3);
  r.Require(mono.max_frames <= window_size + 1, "init.mono.max_frames",
            mono.max_frames, "must be <= window_size + 1");
  r.NonNegative("init.mono.min_span_s", mono.min_span_s);
  r.Require(mono.min_span_s <= mono.window_s, "init.mono.min_span_s",
            mono.min_span_s, "must be <= init.mono.window_s");
  r.Positive("init.mono.min_parallax_px", mono.min_parallax_px);
  r.AtLeast("init.mono.min_correspondences", mono.min_correspondences, 8);
  r.AtLeast("init.mono.min_inliers", mono.min_inliers, 8);
  r.Positive("init.mono.ransac_threshold_px", mono.ransac_threshold_px);
  r.AtLeast("init.mono.min_pnp_inliers", mono.min_pnp_inliers, 6);
  r.Positive("init.mono.pnp_threshold_px", mono.pnp_threshold_px);
  r.Positive("init.mono.max_reprojection_rms_px", mono.max_reprojection_rms_px);
  r.AtLeast("init.mono.bundle_iterations", mono.bundle_iterations, 1);
  r.Positive("init.mono.outlier_threshold_px", mono.outlier_threshold_px);
  r.AtLeast("init.mono.outlier_rounds", mono.outlier_rounds, 0);
  r.Positive("init.mono.max_outlier_share", mono.max_outlier_share);
  r.AtLeast("init.mono.refine_outlier_rounds", mono.refine_outlier_rounds, 0);
  r.NonNegative("init.mono.min_imu_excitation", mono.min_imu_excitation);
  r.Positive("init.mono.max_scale_uncertainty", mono.max_scale_uncertainty);
  r.Positive("init.mono.max_refined_scale_uncertainty",
             mono.max_refined_scale_uncertainty);
  r.AtLeast("init.mono.gyro_min_tracks", mono.gyro_min_tracks, 8);
  r.Positive("init.mono.gyro_min_parallax_px", mono.gyro_min_parallax_px);
  r.Positive("init.mono.gyro_max_refine_change_sigmas",
             mono.gyro_max_refine_change_sigmas);
  r.NonNegative("init.mono.realign_after_s", mono.realign_after_s);
  r.Positive("init.mono.realign_window_s", mono.realign_window_s);
  r.Positive("init.mono.realign_max_scale_uncertainty",
             mono.realign_max_scale_uncertainty);
  r.NonNegative("init.mono.realign_min_change", mono.realign_min_change);
  r.Positive("init.stereo.window_s", stereo.window_s);
  r.Positive("init.stereo.min_span_s", stereo.min_span_s);
  r.Require(stereo.min_span_s <= stereo.window_s, "init.stereo.min_span_s",
            stereo.min_span_s, "must be <= init.stereo.window_s");
  r.AtLeast("init.stereo.min_stereo_points", stereo.min_stereo_points, 6);
  r.AtLeast("init.stereo.min_pnp_inliers", stereo.min_pnp_inliers, 6);
  r.Positive("init.stereo.pnp_threshold_px", stereo.pnp_threshold_px);
  r.AtLeast("init.stereo.refine_outlier_rounds", stereo.refine_outlier_rounds,
            0);
  r.Positive("init.stereo.refine_outlier_threshold_px",
             stereo.refine_outlier_threshold_px);
  r.AtLeast("init.stereo.refine_prescreen_threshold_px",
            stereo.refine_prescreen_threshold_px, 0.0);
  r.Positive("init.stereo.max_refine_scale_change",
             stereo.max_refine_scale_change);
  r.Positive("init.max_rotation_misfit_deg", max_rotation_misfit_deg);
  r.Positive("init.max_gravity_error", max_gravity_error);
  r.Positive("init.max_speed_m_s", max_speed_m_s);
  r.AtLeast("init.refine_iterations", refine_iterations, 0);
  r.Positive("init.max_refine_scale_change", max_refine_scale_change);
  r.Positive("init.refine_tilt_rad", refine_tilt_rad);
  return r.Done(message);
}

bool ZeroVelocityOptions::Validate(std::string* message) const {
  OptionRules r;
  r.Positive("zero_velocity.imu_window_s", imu_window_s);
  r.Require(
      std::isfinite(block_s) && block_s > 0.0 && block_s <= 0.5 * imu_window_s,
      "zero_velocity.block_s", block_s,
      "must be in (0, zero_velocity.imu_window_s / 2]");
  r.Positive("zero_velocity.max_acc_std", max_acc_std);
  r.Positive("zero_velocity.max_gyr_std", max_gyr_std);
  r.Positive("zero_velocity.image_span_s", image_span_s);
  r.Positive("zero_velocity.max_disparity_px", max_disparity_px);
  r.AtLeast("zero_velocity.min_common_features", min_common_features, 1);
  r.NonNegative("zero_velocity.max_speed_without_image_m_s",
                max_speed_without_image_m_s);
  r.Positive("zero_velocity.sigma_position_m", sigma_position_m);
  r.Positive("zero_velocity.sigma_rotation_rad", sigma_rotation_rad);
  r.Positive("zero_velocity.sigma_velocity_m_s", sigma_velocity_m_s);
  return r.Done(message);
}

}  // namespace vio
