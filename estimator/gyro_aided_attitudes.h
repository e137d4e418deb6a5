#ifndef VIO_ESTIMATOR_GYRO_AIDED_ATTITUDES_H_
#define VIO_ESTIMATOR_GYRO_AIDED_ATTITUDES_H_

// The frame attitudes of a gyroscope-aided window as a function of the
// gyroscope bias: R_v_bk(b_g) = Exp-corrected rotation from frame 0 to
// frame k (first-order in b_g about the integration's bias, as
// PreintegratedImu::Corrected), R_v_b0 = I.
//
// What the rotation-only steps of the gyroscope-aided start need (the bias
// from the rotations, gyro_bias_from_rotations.h; the rotation-compensated
// parallax, gyro_aided_parallax.h): built from the rotation-only
// integration (preintegration/gyro_rotation.h, one pass over the samples)
// for the initialiser's cheap precheck, or from a problem's full
// preintegrations; both give the same attitudes up to rounding.

#include <Eigen/Core>
#include <vector>

#include "preintegration/gyro_rotation.h"
#include "preintegration/imu_preintegration.h"

namespace vio {

class GyroAidedAttitudes {
 public:
  // from_first[k - 1]: the rotation from frame 0 to frame k.
  explicit GyroAidedAttitudes(std::vector<GyroRotation> from_first);
  // The rotation parts of preintegrations from frame 0 (GyroAidedProblem's
  // from_first).
  static GyroAidedAttitudes Of(const std::vector<ImuPreintegration>& from_first);

  int NumFrames() const { return static_cast<int>(from_first_.size()) + 1; }

  // Every frame's camera attitude R_v_ck = R_v_bk(b_g) R_b_c.
  std::vector<Eigen::Matrix3d> CameraAttitudes(
      const Eigen::Vector3d& b_g, const Eigen::Matrix3d& R_b_c) const;

 private:
  std::vector<GyroRotation> from_first_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_AIDED_ATTITUDES_H_
