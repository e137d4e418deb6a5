#include "eval/nees.h"

#include "geometry/so3.h"

namespace vio {

PoseNees ComputePoseNees(const StampedPose& estimate, const StampedPose& truth,
                         const Eigen::Matrix<double, 6, 6>& covariance) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = estimate.p_w_b - truth.p_w_b;
  e.tail<3>() = Log(truth.q_w_b.conjugate() * estimate.q_w_b);
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(covariance);
  PoseNees n;
  n.pose = e.dot(ldlt.solve(e));
  const Eigen::Matrix3d P_p = covariance.topLeftCorner<3, 3>();
  const Eigen::Matrix3d P_r = covariance.bottomRightCorner<3, 3>();
  n.position = e.head<3>().dot(P_p.ldlt().solve(Eigen::Vector3d(e.head<3>())));
  n.rotation = e.tail<3>().dot(P_r.ldlt().solve(Eigen::Vector3d(e.tail<3>())));
  // The yaw error: the body-frame error's component along world z seen in
  // the body, u = R^T e_z (R Exp(d) = Exp(R d) R turns about R d).
  const Eigen::Vector3d u =
      estimate.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  const double yaw = u.dot(e.tail<3>());
  n.yaw = yaw * yaw / u.dot(P_r * u);
  return n;
}

Eigen::Isometry3d GaugeTransform(const StampedPose& first_estimate,
                                 const StampedPose& first_truth) {
  // A turn by a about world z moves the body-frame error's yaw component
  // (along u = R^T e_z) by -a: two first-order steps reach 1e-12 rad.
  double a = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Quaterniond q_t =
        Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ())) *
        first_truth.q_w_b;
    const Eigen::Vector3d error = Log(q_t.conjugate() * first_estimate.q_w_b);
    a += error.dot(q_t.conjugate() * Eigen::Vector3d::UnitZ());
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = first_estimate.p_w_b - T.linear() * first_truth.p_w_b;
  return T;
}

StampedPose Transform(const Eigen::Isometry3d& T, const StampedPose& pose) {
  StampedPose out = pose;
  out.p_w_b = T * pose.p_w_b;
  out.q_w_b = Eigen::Quaterniond(T.linear()) * pose.q_w_b;
  return out;
}

}  // namespace vio
