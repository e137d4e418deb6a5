#include "estimator/gyro_aided_attitudes.h"

#include <utility>

namespace vio {

GyroAidedAttitudes::GyroAidedAttitudes(std::vector<GyroRotation> from_first)
    : from_first_(std::move(from_first)) {}

GyroAidedAttitudes GyroAidedAttitudes::Of(
    const std::vector<ImuPreintegration>& from_first) {
  std::vector<GyroRotation> rotations;
  rotations.reserve(from_first.size());
  for (const ImuPreintegration& imu : from_first) {
    const PreintegratedImu& r = imu.result();
    GyroRotation g;
    g.t0_ns = r.t0_ns;
    g.t1_ns = r.t1_ns;
    g.delta_q = r.delta.q;
    g.d_dq_d_bg = r.d_dq_d_bg;
    g.lin_b_g = r.lin_b_g;
    rotations.push_back(g);
  }
  return GyroAidedAttitudes(std::move(rotations));
}

std::vector<Eigen::Matrix3d> GyroAidedAttitudes::CameraAttitudes(
    const Eigen::Vector3d& b_g, const Eigen::Matrix3d& R_b_c) const {
  std::vector<Eigen::Matrix3d> R_v_c(NumFrames());
  R_v_c[0] = Eigen::Matrix3d::Identity() * R_b_c;
  for (size_t k = 0; k < from_first_.size(); ++k) {
    // As FrameState (gyro_aided_solver.h) forms R_v_b.
    R_v_c[k + 1] =
        from_first_[k].Corrected(b_g).normalized().toRotationMatrix() * R_b_c;
  }
  return R_v_c;
}

}  // namespace vio
