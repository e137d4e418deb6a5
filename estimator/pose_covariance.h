#ifndef VIO_ESTIMATOR_POSE_COVARIANCE_H_
#define VIO_ESTIMATOR_POSE_COVARIANCE_H_

// The uncertainty the estimator claims for a pose: the covariance of one pose
// block of a window problem at its current values, the inverse of the
// Gauss-Newton information J^T J of every residual in the problem (the
// marginalisation prior, the IMU factors, the visual factors with their
// robust weights as Ceres applies them), with every other block (the other
// poses, speed-biases, inverse depths) marginalised. Computed by
// ceres::Covariance (sparse QR of the Jacobian), on the pose's tangent
// space: [dt (world, m), dtheta (body, rad)], the project's perturbation
// t + dt, q (x) Exp(dtheta) (factors/pose_manifold.h).
//
// Used to check consistency: over many runs, the NEES e^T P^-1 e of the
// error e against the truth should average the dimension (6) when P is
// honest (docs/recorded_flights.md, tools/vio_nees).

#include <ceres/problem.h>

#include <Eigen/Core>

namespace vio {

// The 6x6 covariance of `pose` (a block of `problem`, 7 values, with our
// PoseManifold). False when Ceres cannot compute it (the information is
// rank deficient: a direction no residual constrains).
bool PoseCovariance(ceres::Problem* problem, const double* pose,
                    Eigen::Matrix<double, 6, 6>* covariance);

}  // namespace vio

#endif  // VIO_ESTIMATOR_POSE_COVARIANCE_H_
