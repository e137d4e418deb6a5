#ifndef VIO_ESTIMATOR_MONO_INITIALIZER_H_
#define VIO_ESTIMATOR_MONO_INITIALIZER_H_

// The monocular start in motion: over the frames of the last
// init.mono.window_s (at most init.mono.max_frames of them),
//   1. checks the IMU excitation (in_motion_start.h, ImuExcitation);
//   2. solves the up-to-scale structure from motion (structure_from_motion.h);
//   3. aligns it with the IMU: gyroscope bias, velocities, gravity, metric
//      scale (in_motion_start.h, AlignAndBuild).
// Each step's check may refuse the start; the caller retries on a later
// frame. The joint visual-inertial adjustment that completes the start runs
// in the estimator (it owns the window).

#include <Eigen/Geometry>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "preintegration/imu_types.h"

namespace vio {

class MonoInitializer {
 public:
  // T_b_c, focal_px: camera 0.
  MonoInitializer(const EstimatorOptions& options,
                  const Eigen::Isometry3d& T_b_c, double focal_px,
                  const ImuNoise& noise,
                  const PreintegrationOptions& preintegration);

  // Tries to start at the newest of `frames` (oldest first) with the IMU
  // samples `imu` (covering them). On success fills *window and returns an
  // attempt with reason kNone; otherwise the reason, value and limit (method
  // kMono, t_ns the newest frame's stamp). Never throws on bad data.
  // The frames of init.mono.long_window_s are tried first (the start then
  // waits in the estimator for a well-determined scale); when their
  // structure from motion fails over more than window_s, those of window_s.
  InitAttempt TryInitialize(const std::vector<BufferedFrame>& frames,
                            const std::vector<ImuSample>& imu,
                            InitialWindow* window) const;

 private:
  // The attempt over the frames of the last window_s seconds.
  InitAttempt TryWindow(const std::vector<BufferedFrame>& frames,
                        const std::vector<ImuSample>& imu, double window_s,
                        InitialWindow* window) const;

  EstimatorOptions options_;
  Eigen::Isometry3d T_b_c_;
  double focal_px_;
  ImuNoise noise_;
  PreintegrationOptions preintegration_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_MONO_INITIALIZER_H_
