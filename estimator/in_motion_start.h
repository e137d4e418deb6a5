#ifndef VIO_ESTIMATOR_IN_MOTION_START_H_
#define VIO_ESTIMATOR_IN_MOTION_START_H_

// What the two in-motion initialisers (mono_initializer.h,
// stereo_initializer.h) share: choosing the frames, preintegrating the IMU
// between them, and turning a visual trajectory into the first window by
// visual-inertial alignment (visual_inertial_alignment.h) with the start's
// checks:
//   - the visual rotations agree with the gyroscope once its bias is fitted
//     (init.max_rotation_misfit_deg);
//   - the free alignment's |g| is near the configured g (max_gravity_error);
//   - mono: the scale is positive and its relative std small
//     (mono.max_scale_uncertainty);
//   - no velocity beyond init.max_speed_m_s.
// The window is gravity aligned, with the newest frame at the origin and yaw
// 0; b_a is the alignment's estimate (under the state_prior.accel_bias prior).

#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "preintegration/imu_preintegration.h"

namespace vio {

// Indices of the frames of the last window_s seconds, at most max_frames of
// them evenly spread over that span, the newest always last.
std::vector<int> SelectFrames(const std::vector<BufferedFrame>& frames,
                              double window_s, int max_frames);

// Span of the selected frames [s].
double SpanSeconds(const std::vector<BufferedFrame>& frames,
                   const std::vector<int>& selected);

// The IMU intervals between consecutive selected frames, preintegrated with
// zero biases. False when the IMU does not cover one (a gap, missing data).
bool PreintegrateSelected(const std::vector<BufferedFrame>& frames,
                          const std::vector<int>& selected,
                          const std::vector<ImuSample>& imu,
                          const ImuNoise& noise,
                          const PreintegrationOptions& preintegration,
                          std::vector<ImuPreintegration>* intervals);

// The standard deviation over the intervals of their mean specific force
// dv / T in the body frame [m/s^2] (VINS-Mono's excitation test): near zero
// for constant velocity and for a constant-speed turn.
double ImuExcitation(const std::vector<ImuPreintegration>& intervals);

// A visual trajectory of the selected frames in a frame v of its own.
struct VisualTrajectory {
  std::vector<Eigen::Isometry3d> T_v_c;  // camera 0, per selected frame
  std::map<int64_t, Eigen::Vector3d> points_v;
  bool metric = false;  // stereo: metres; mono: the scale is estimated
};

// Aligns the trajectory with the intervals (re-propagated with the fitted
// gyroscope bias) and fills *window (method, frames, points, diagnostics'
// alignment figures). Returns the attempt with reason kNone on success.
InitAttempt AlignAndBuild(const VisualTrajectory& visual,
                          const std::vector<BufferedFrame>& frames,
                          const std::vector<int>& selected,
                          const Eigen::Isometry3d& T_b_c,
                          const EstimatorOptions& options,
                          std::vector<ImuPreintegration>* intervals,
                          InitialWindow* window);

}  // namespace vio

#endif  // VIO_ESTIMATOR_IN_MOTION_START_H_
