#ifndef VIO_ESTIMATOR_STATE_CHECK_H_
#define VIO_ESTIMATOR_STATE_CHECK_H_

// The check before every solve: may the window's values be handed to Ceres?
// A non-finite value in a pose block makes Ceres stop the program (its
// manifold check fails when the block is added), and an exploding state (a
// speed no vehicle reaches, from a glitch the IMU range check let through)
// only drags the window along. Either way the estimator resets instead.

#include "estimator/feature_manager.h"
#include "estimator/window.h"

namespace vio {

enum class StateDefect {
  kNone,
  kNonFinite,    // a pose, speed-bias, extrinsic, t_d or inverse depth
  kBadRotation,  // a quaternion far from unit length (|q| outside [0.5, 2])
  kTooFast,      // |v| > max_speed_m_s for some frame
};

const char* StateDefectName(StateDefect defect);

// The first defect found over every frame, the extrinsics, t_d and the
// triangulated landmarks; kNone when the window may be solved.
StateDefect CheckWindowState(const Window& window,
                             const FeatureManager& features,
                             double max_speed_m_s);

}  // namespace vio

#endif  // VIO_ESTIMATOR_STATE_CHECK_H_
