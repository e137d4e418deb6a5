#ifndef VIO_GEOMETRY_POSE_SPLINE_H_
#define VIO_GEOMETRY_POSE_SPLINE_H_

// A uniform cubic B-spline on positions and, in cumulative form, on SO(3):
// a smooth body trajectory whose first and second time derivatives are
// analytic, so that an IMU can be computed from it (not differenced).
//
// Knots are dt apart from t0. Segment i covers [t0 + i dt, t0 + (i+1) dt) and
// is shaped by control points i..i+3; with u = (t - t0)/dt - i in [0, 1):
//   p(t) = sum_k b_k(u) c_{i+k},
//     b = ((1-u)^3, 3u^3 - 6u^2 + 4, -3u^3 + 3u^2 + 3u + 1, u^3) / 6
//   R(t) = R_i * prod_{j=1..3} Exp(B_j(u) d_j),  d_j = Log(R_{i+j-1}^T R_{i+j})
//     cumulative basis B_j = sum_{k>=j} b_k:
//     B_1 = (5 + 3u - 3u^2 + u^3)/6, B_2 = (1 + 3u + 3u^2 - 2u^3)/6, B_3 =
//     u^3/6.
// Near time t0 + k dt the curve is close to control point k+1 (the curve
// does not interpolate its control points).
//
// Angular velocity and acceleration in the body frame follow the recursion of
// Sommer et al., "Efficient Derivative Computation for Cumulative B-Splines on
// Lie Groups", CVPR 2020 (derived again in pose_spline.cc): with
// A_j = Exp(B_j d_j),
//   w_j = A_j^T w_{j-1} + B_j' d_j,                   w_0 = 0,
//   a_j = A_j^T a_{j-1} + (A_j^T w_{j-1}) x (B_j' d_j) + B_j'' d_j,  a_0 = 0,
// (time derivatives: B' = dB/du / dt), the last terms w_3, a_3 being the
// body rate and its derivative. Rotation Jacobians with respect to the control
// rotations use the project's right perturbation R (+) e = R Exp(e).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace vio {

// The spline's value and derivatives at one time.
struct PoseSplineState {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();            // position [m]
  Eigen::Vector3d v = Eigen::Vector3d::Zero();            // dp/dt [m/s]
  Eigen::Vector3d a = Eigen::Vector3d::Zero();            // d2p/dt2 [m/s^2]
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // rotation
  Eigen::Vector3d w = Eigen::Vector3d::Zero();   // body angular rate [rad/s]
  Eigen::Vector3d dw = Eigen::Vector3d::Zero();  // its derivative [rad/s^2]
};

class PoseSpline {
 public:
  static constexpr int kOrder = 4;  // control points per segment

  // dt > 0 [s]; positions and rotations of equal size >= 4. Throws
  // std::invalid_argument otherwise.
  PoseSpline(double t0_s, double dt_s, std::vector<Eigen::Vector3d> positions,
             std::vector<Eigen::Quaterniond> rotations);

  // The spline at t in [start_s(), end_s()] (the end belongs to the last
  // segment). Throws std::out_of_range outside.
  PoseSplineState Evaluate(double t) const;

  // The rotation at t and, when d_R_d_ctrl is not null, its Jacobians with
  // respect to right perturbations of control rotations *first .. *first + 3:
  //   R(t; R_k Exp(e_k)) ~= R(t) Exp(sum_k d_R_d_ctrl[k] e_k).
  Eigen::Quaterniond Rotation(double t,
                              std::array<Eigen::Matrix3d, kOrder>* d_R_d_ctrl,
                              int* first) const;

  // The segment of t and its u in [0, 1] (the end maps to the last segment,
  // u = 1). Throws std::out_of_range outside the span.
  int Segment(double t, double* u) const;

  // The standard basis b_k(u) of the position (see above) and its first and
  // second derivatives with respect to u.
  static Eigen::Vector4d Basis(double u, int derivative);

  double start_s() const { return t0_; }
  double end_s() const {
    return t0_ + dt_ * static_cast<double>(positions_.size() - 3);
  }
  double dt_s() const { return dt_; }
  const std::vector<Eigen::Vector3d>& positions() const { return positions_; }
  const std::vector<Eigen::Quaterniond>& rotations() const {
    return rotations_;
  }

 private:
  double t0_;
  double dt_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Quaterniond> rotations_;
};

}  // namespace vio

#endif  // VIO_GEOMETRY_POSE_SPLINE_H_
