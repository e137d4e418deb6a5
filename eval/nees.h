#ifndef VIO_EVAL_NEES_H_
#define VIO_EVAL_NEES_H_

// Consistency of an estimate with the uncertainty it claims: the normalised
// estimation error squared (NEES, Bar-Shalom et al., "Estimation with
// Applications to Tracking and Navigation", 2001, sec. 5.4), as OpenVINS
// reports it. For a pose with error e and claimed covariance P,
//   NEES = e^T P^-1 e,   e = [p_est - p_true (world), Log(R_true^T R_est)
//                             (body)],
// the tangent of the project's perturbation (t + dt, R Exp(dtheta)). Averaged
// over many independent runs it equals the dimension (6) when P is honest;
// above it the estimator is overconfident.
//
// A VIO estimate lives in its own world frame: position and yaw are fixed by
// the gauge prior at the first frame. GaugeTransform maps the truth into that
// frame (the first estimate, the prior's centre, and the truth at the same
// instant then agree in position and in yaw about world z; tilt is
// observable and not aligned), so errors are measured as the estimator's
// covariance describes them.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dataset/trajectory.h"

namespace vio {

struct PoseNees {
  double pose = 0.0;      // 6 dof
  double position = 0.0;  // 3 dof, its own 3x3 block of P
  double rotation = 0.0;  // 3 dof
  double yaw = 0.0;       // 1 dof: the rotation error about world z
};

// NEES of `estimate` against `truth` (already in the estimate's frame) under
// `covariance` (tangent [dt, dtheta], positive definite).
PoseNees ComputePoseNees(const StampedPose& estimate, const StampedPose& truth,
                         const Eigen::Matrix<double, 6, 6>& covariance);

// The transform T (p -> R p + t, R a rotation about world z) with
// T * first_truth matching first_estimate in position and in yaw.
Eigen::Isometry3d GaugeTransform(const StampedPose& first_estimate,
                                 const StampedPose& first_truth);

// T * pose: both position and attitude moved into the estimate's frame.
StampedPose Transform(const Eigen::Isometry3d& T, const StampedPose& pose);

}  // namespace vio

#endif  // VIO_EVAL_NEES_H_
