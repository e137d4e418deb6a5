#ifndef VIO_ESTIMATOR_GYRO_AIDED_PARALLAX_H_
#define VIO_ESTIMATOR_GYRO_AIDED_PARALLAX_H_

// The parallax a gyroscope-aided problem's tracks keep once the gyroscope's
// rotation (at a given bias) is taken out: what tells translation from a
// pure rotation (gyro_aided_initializer.h). It needs the frame attitudes
// alone, so it can be judged at the bias fitted to the rotations alone
// (gyro_bias_from_rotations.h), before the costly fit on the reprojection
// errors: the initialiser's cheap precheck.

#include <Eigen/Core>
#include <vector>

#include "estimator/gyro_aided_attitudes.h"
#include "estimator/gyro_aided_solver.h"

namespace vio {

// A track's largest parallax against its anchor once the rotation of the
// camera attitudes R_v_c (indexed by the sightings' frames) is taken out:
// the distance between a later sighting and where the anchor's ray would
// appear under rotation alone [px] (infinite when that ray points behind the
// later camera).
double TrackParallaxPx(const std::vector<Eigen::Matrix3d>& R_v_c,
                       double focal_px, const GyroAidedTrack& track);

// The same with the attitudes of a solution (its gyroscope bias).
double TrackParallaxPx(const GyroAidedProblem& problem,
                       const GyroAidedSolution& solution,
                       const GyroAidedTrack& track);

// The median over the problem's tracks of TrackParallaxPx with `attitudes`
// at gyroscope bias b_g [px]; 0 without tracks. Uses the problem's tracks,
// camera and focal length, not its preintegrations (which may be empty).
double MedianRotationParallaxPx(const GyroAidedProblem& problem,
                                const GyroAidedAttitudes& attitudes,
                                const Eigen::Vector3d& b_g);

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_AIDED_PARALLAX_H_
