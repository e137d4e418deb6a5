#ifndef VIO_ESTIMATOR_GYRO_BIAS_FROM_ROTATIONS_H_
#define VIO_ESTIMATOR_GYRO_BIAS_FROM_ROTATIONS_H_

// The gyroscope bias from the frame-to-frame rotations alone, whatever the
// translation (Kneip and Lynen, "Direct optimization of frame-to-frame
// rotation", ICCV 2013): for frames i and j = i + 4 (0.2 s apart at 20 Hz)
// sharing features with unit bearings u, every n = u_i x (R_ij u_j) is
// orthogonal to the translation between them, so the smallest eigenvalue of
// M_ij = sum n n^T vanishes when the rotation R_ij (the gyroscope's, at the
// bias) is right, for any translation and scale. The bias minimises
// sum_ij lambda_min(M_ij(b_g)) (Newton with central-difference derivatives,
// three components, steps of at most 0.05 rad/s). Measured on the hand-held
// preset it gets within ~0.03 rad/s with 1 px of feature noise (0.2 s of
// baseline leaves the rotation and the translation hard to tell apart): the
// start of the gyroscope-aided start's own fit (gyro_aided_solver.h).

#include <Eigen/Core>
#include <vector>

#include "estimator/gyro_aided_attitudes.h"
#include "estimator/gyro_aided_solver.h"

namespace vio {

// Refines *b_g (the start) over the tracks and the frames of `attitudes`
// (the tracks' frame indices index them; R_b_c: camera 0). False with fewer
// than three frame pairs sharing eight features.
bool FitGyroBiasFromRotations(const GyroAidedAttitudes& attitudes,
                              const std::vector<GyroAidedTrack>& tracks,
                              const Eigen::Matrix3d& R_b_c,
                              Eigen::Vector3d* b_g);

// The same over a problem's tracks, with the attitudes of its
// preintegrations.
bool FitGyroBiasFromRotations(const GyroAidedProblem& problem,
                              Eigen::Vector3d* b_g);

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_BIAS_FROM_ROTATIONS_H_
