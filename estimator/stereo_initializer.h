#ifndef VIO_ESTIMATOR_STEREO_INITIALIZER_H_
#define VIO_ESTIMATOR_STEREO_INITIALIZER_H_

// The stereo start in motion: over the frames of the last init.stereo.window_s
// (spanning at least init.stereo.min_span_s),
//   1. the oldest frame's stereo pairs give metric points (estimator/
//      triangulation.h with the calibrated T_c0_c1);
//   2. every later frame is placed by PnP on them (structure_from_motion.h,
//      PlaceCameraByPnp), newest last, and adds its own stereo pairs not
//      seen before to the points the next frames are placed on;
//   3. the metric trajectory is aligned with the IMU: gyroscope bias,
//      velocities and gravity, the scale held at 1 (in_motion_start.h; its
//      checks, the free |g| in its own sigmas and the rotation misfit, are
//      set for a failed PnP, not for the PnP's own errors, which the joint
//      adjustment removes).
// No stillness and no IMU excitation are needed: the scale comes from the
// stereo baseline, and gravity shows in the specific force whatever the
// motion. The joint visual-inertial adjustment that completes the start runs
// in the estimator.

#include <Eigen/Geometry>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "preintegration/imu_types.h"

namespace vio {

class StereoInitializer {
 public:
  // T_b_c0, T_b_c1: the two cameras; focal_px: camera 0's.
  StereoInitializer(const EstimatorOptions& options,
                    const Eigen::Isometry3d& T_b_c0,
                    const Eigen::Isometry3d& T_b_c1, double focal_px,
                    const ImuNoise& noise,
                    const PreintegrationOptions& preintegration);

  // As MonoInitializer::TryInitialize (method kStereo).
  InitAttempt TryInitialize(const std::vector<BufferedFrame>& frames,
                            const std::vector<ImuSample>& imu,
                            InitialWindow* window) const;

 private:
  EstimatorOptions options_;
  Eigen::Isometry3d T_b_c0_;
  Eigen::Isometry3d T_c0_c1_;
  double focal_px_;
  ImuNoise noise_;
  PreintegrationOptions preintegration_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_STEREO_INITIALIZER_H_
