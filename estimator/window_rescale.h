#ifndef VIO_ESTIMATOR_WINDOW_RESCALE_H_
#define VIO_ESTIMATOR_WINDOW_RESCALE_H_

// Multiplies the window's metric scale by s about a centre c (the newest
// frame's position, so that the estimate does not jump): what a corrected
// monocular scale asks of the running state (estimator/scale_realignment.h).
//   positions     p  -> c + s (p - c)       (frames, world points and their
//                                            first estimates)
//   velocities    v  -> s v
//   inverse depth rho -> rho / s            (the anchor camera's depth grows
//                                            by s: exact when the camera sits
//                                            at the body origin, otherwise
//                                            off by the lever arm, which the
//                                            next solve takes up)
// Attitudes, biases, extrinsics and the time offset are unchanged.
//
// The marginalisation prior r = r0 + J (x (-) x0) is rewritten in the new
// coordinates x' = S(x): x0' = S(x0) and, since on a scaled entry
// x - x0 = (x' - x0') / s, J's columns of positions, velocities and world
// points are divided by s. So the prior says what it said before about the
// rescaled state: its minimum moves with the state instead of pulling the
// window back to the old scale.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "factors/marginalization_prior.h"

namespace vio {

// A similarity about c and an accelerometer-bias shift:
//   p -> c + s R (p - c),  v -> s R v,  q -> R q,  b_a -> b_a + delta_b_a.
struct WindowCorrection {
  double s = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();      // a world rotation
  Eigen::Vector3d c = Eigen::Vector3d::Zero();          // [m]
  Eigen::Vector3d delta_b_a = Eigen::Vector3d::Zero();  // [m/s^2]
};

// Applies the correction to the window's frames and the feature manager's
// landmarks.
void CorrectWindow(const WindowCorrection& k, Window* window,
                   FeatureManager* features);

// The prior in the rescaled coordinates. `blocks` are its parameter blocks
// (addresses); a block is recognised as a frame pose, a frame speed-bias or a
// world point of `window` / `features` by its address (any other block is
// kept as it is). Call before RescaleWindow or after: only addresses are
// read from the window and the features.
std::unique_ptr<MarginalizationPrior> CorrectPrior(
    const MarginalizationPrior& prior, const std::vector<double*>& blocks,
    const WindowCorrection& k, const Window& window,
    const FeatureManager& features);

}  // namespace vio

#endif  // VIO_ESTIMATOR_WINDOW_RESCALE_H_
