#include "estimator/estimator_options.h"

#include <cmath>

#include "estimator/option_rules.h"

namespace vio {

const char* ReanchoredTracksName(ReanchoredTracks r) {
  switch (r) {
    case ReanchoredTracks::kReuse:
      return "reuse";
    case ReanchoredTracks::kKeepPoint:
      return "keep_point";
    case ReanchoredTracks::kKeepPointFirstEstimate:
      return "keep_point_fej";
  }
  return "?";
}

bool ParseReanchoredTracks(const std::string& name, ReanchoredTracks* r) {
  for (ReanchoredTracks c :
       {ReanchoredTracks::kReuse, ReanchoredTracks::kKeepPoint,
        ReanchoredTracks::kKeepPointFirstEstimate}) {
    if (name == ReanchoredTracksName(c)) {
      *r = c;
      return true;
    }
  }
  return false;
}

bool EstimatorOptions::Validate(std::string* message) const {
  OptionRules c;
  c.AtLeast("window_size", window_size, 2);
  c.Positive("gravity_magnitude", gravity_magnitude);
  c.Finite("initial_time_offset_s", initial_time_offset_s);
  c.NonNegative("keyframe.min_parallax_px", keyframe.min_parallax_px);
  c.NonNegative("keyframe.min_tracked_features", keyframe.min_tracked_features);
  c.NonNegative("triangulation.min_parallax_deg",
                triangulation.min_parallax_deg);
  c.Positive("triangulation.min_depth_m", triangulation.min_depth_m);
  c.Require(std::isfinite(triangulation.max_depth_m) &&
                triangulation.max_depth_m > triangulation.min_depth_m,
            "triangulation.max_depth_m", triangulation.max_depth_m,
            "must be > triangulation.min_depth_m");
  c.AtLeast("triangulation.min_observations", triangulation.min_observations,
            2);
  c.Positive("landmarks.outlier_threshold_px", landmarks.outlier_threshold_px);
  c.AtLeast("landmarks.max_landmarks", landmarks.max_landmarks, 1);
  c.AtLeast("landmarks.max_world_points", landmarks.max_world_points, 0);
  c.NonNegative("landmarks.reuse_after_moving_start_s",
                landmarks.reuse_after_moving_start_s);
  c.Positive("static_init.window_s", static_init.window_s);
  c.Require(std::isfinite(static_init.block_s) && static_init.block_s > 0.0 &&
                static_init.block_s <= 0.5 * static_init.window_s,
            "static_init.block_s", static_init.block_s,
            "must be in (0, static_init.window_s / 2]");
  c.Positive("static_init.max_acc_std", static_init.max_acc_std);
  c.Positive("static_init.max_gyr_std", static_init.max_gyr_std);
  c.Positive("state_prior.position_m", state_prior.position_m);
  c.Positive("state_prior.yaw_rad", state_prior.yaw_rad);
  c.Positive("state_prior.tilt_rad", state_prior.tilt_rad);
  c.Positive("state_prior.velocity_still", state_prior.velocity_still);
  c.Positive("state_prior.velocity_moving", state_prior.velocity_moving);
  c.Positive("state_prior.accel_bias", state_prior.accel_bias);
  c.Positive("state_prior.gyro_bias", state_prior.gyro_bias);
  c.Positive("state_prior.extrinsic_rotation_rad",
             state_prior.extrinsic_rotation_rad);
  c.Positive("state_prior.extrinsic_translation_m",
             state_prior.extrinsic_translation_m);
  c.NonNegative("failure.min_tracked_landmarks", failure.min_tracked_landmarks);
  c.Positive("failure.max_accel_bias", failure.max_accel_bias);
  c.Positive("failure.max_gyro_bias", failure.max_gyro_bias);
  c.Positive("failure.max_position_jump_m", failure.max_position_jump_m);
  c.Positive("failure.max_rotation_jump_deg", failure.max_rotation_jump_deg);
  c.Positive("failure.max_speed_m_s", failure.max_speed_m_s);
  c.Positive("imu_stream.rate_hz", imu_stream.rate_hz);
  std::string range_message;
  c.Nested("imu_stream.", imu_stream.range.Validate(&range_message),
           range_message);
  std::string adaptation_message;
  c.Nested("imu_stream.noise_adaptation.",
           imu_stream.noise_adaptation.Validate(&adaptation_message),
           adaptation_message);
  c.AtLeast("solver.max_iterations", solver.max_iterations, 1);
  c.Require(solver.function_tolerance >= 0.0 && solver.function_tolerance < 1.0,
            "solver.function_tolerance", solver.function_tolerance,
            "must be in [0, 1)");
  c.NonNegative("solver.max_time_s", solver.max_time_s);
  c.AtLeast("solver.num_threads", solver.num_threads, 1);
  if (!c.Done(message)) return false;
  return init.Validate(use_stereo, window_size, message) &&
         zero_velocity.Validate(message);
}

}  // namespace vio
