#include "geometry/pose_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/so3.h"

namespace vio {
namespace {

// The cumulative basis B_1..B_3 (index 0..2) and its u-derivatives, from
// B_j = sum_{k>=j} b_k (see the header).
Eigen::Vector3d CumulativeBasis(double u, int derivative) {
  const double u2 = u * u, u3 = u2 * u;
  switch (derivative) {
    case 0:
      return Eigen::Vector3d(5.0 + 3.0 * u - 3.0 * u2 + u3,
                             1.0 + 3.0 * u + 3.0 * u2 - 2.0 * u3, u3) /
             6.0;
    case 1:
      return Eigen::Vector3d(0.5 * (1.0 - u) * (1.0 - u), 0.5 + u - u2,
                             0.5 * u2);
    default:
      return Eigen::Vector3d(u - 1.0, 1.0 - 2.0 * u, u);
  }
}

}  // namespace

PoseSpline::PoseSpline(double t0_s, double dt_s,
                       std::vector<Eigen::Vector3d> positions,
                       std::vector<Eigen::Quaterniond> rotations)
    : t0_(t0_s),
      dt_(dt_s),
      positions_(std::move(positions)),
      rotations_(std::move(rotations)) {
  if (!(std::isfinite(dt_) && dt_ > 0.0) || !std::isfinite(t0_)) {
    throw std::invalid_argument("PoseSpline: dt must be > 0 and t0 finite");
  }
  if (positions_.size() < kOrder || positions_.size() != rotations_.size()) {
    throw std::invalid_argument(
        "PoseSpline: needs as many positions as rotations, at least 4 (got " +
        std::to_string(positions_.size()) + " and " +
        std::to_string(rotations_.size()) + ")");
  }
  for (Eigen::Quaterniond& q : rotations_) q.normalize();
}

Eigen::Vector4d PoseSpline::Basis(double u, int derivative) {
  const double u2 = u * u, u3 = u2 * u;
  switch (derivative) {
    case 0:
      return Eigen::Vector4d((1.0 - u) * (1.0 - u) * (1.0 - u),
                             3.0 * u3 - 6.0 * u2 + 4.0,
                             -3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0, u3) /
             6.0;
    case 1:
      return Eigen::Vector4d(-(1.0 - u) * (1.0 - u), 3.0 * u2 - 4.0 * u,
                             -3.0 * u2 + 2.0 * u + 1.0, u2) /
             2.0;
    default:
      return Eigen::Vector4d(1.0 - u, 3.0 * u - 2.0, 1.0 - 3.0 * u, u);
  }
}

int PoseSpline::Segment(double t, double* u) const {
  const int segments = static_cast<int>(positions_.size()) - 3;
  const double s = (t - t0_) / dt_;
  // A rounding tolerance of 1e-9 segment at both ends.
  if (!(s >= -1e-9 && s <= segments + 1e-9)) {
    throw std::out_of_range("PoseSpline: t = " + std::to_string(t) +
                            " s is outside [" + std::to_string(start_s()) +
                            ", " + std::to_string(end_s()) + "] s");
  }
  int i = static_cast<int>(std::floor(s));
  i = std::min(std::max(i, 0), segments - 1);
  *u = std::min(std::max(s - i, 0.0), 1.0);
  return i;
}

PoseSplineState PoseSpline::Evaluate(double t) const {
  double u = 0.0;
  const int i = Segment(t, &u);
  PoseSplineState state;
  const Eigen::Vector4d b = Basis(u, 0);
  const Eigen::Vector4d db = Basis(u, 1) / dt_;
  const Eigen::Vector4d ddb = Basis(u, 2) / (dt_ * dt_);
  for (int k = 0; k < kOrder; ++k) {
    state.p += b[k] * positions_[i + k];
    state.v += db[k] * positions_[i + k];
    state.a += ddb[k] * positions_[i + k];
  }
  // R = R_i A_1 A_2 A_3. Differentiating R_j = R_{j-1} A_j with
  // dA_j/dt = A_j [B_j' d_j]x gives [w_j]x = R_j^T dR_j/dt
  //   = A_j^T [w_{j-1}]x A_j + [B_j' d_j]x  ->  w_j = A_j^T w_{j-1} + B_j' d_j.
  // Once more, with d(A_j^T)/dt = -[B_j' d_j]x A_j^T:
  //   dw_j = A_j^T dw_{j-1} - (B_j' d_j) x (A_j^T w_{j-1}) + B_j'' d_j.
  const Eigen::Vector3d B = CumulativeBasis(u, 0);
  const Eigen::Vector3d dB = CumulativeBasis(u, 1) / dt_;
  const Eigen::Vector3d ddB = CumulativeBasis(u, 2) / (dt_ * dt_);
  Eigen::Quaterniond q = rotations_[i];
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  Eigen::Vector3d dw = Eigen::Vector3d::Zero();
  for (int j = 1; j < kOrder; ++j) {
    const Eigen::Vector3d d =
        Log(rotations_[i + j - 1].conjugate() * rotations_[i + j]);
    const Eigen::Quaterniond A = ExpQuaternion(B[j - 1] * d);
    const Eigen::Matrix3d At = A.conjugate().toRotationMatrix();
    const Eigen::Vector3d rate = dB[j - 1] * d;
    const Eigen::Vector3d w_rotated = At * w;
    dw = At * dw + w_rotated.cross(rate) + ddB[j - 1] * d;
    w = w_rotated + rate;
    q = q * A;
  }
  state.q = q.normalized();
  state.w = w;
  state.dw = dw;
  return state;
}

Eigen::Quaterniond PoseSpline::Rotation(
    double t, std::array<Eigen::Matrix3d, kOrder>* d_R_d_ctrl,
    int* first) const {
  double u = 0.0;
  const int i = Segment(t, &u);
  if (first != nullptr) *first = i;
  const Eigen::Vector3d B = CumulativeBasis(u, 0);
  std::array<Eigen::Vector3d, kOrder> d;
  std::array<Eigen::Quaterniond, kOrder> A;
  Eigen::Quaterniond q = rotations_[i];
  for (int j = 1; j < kOrder; ++j) {
    d[j] = Log(rotations_[i + j - 1].conjugate() * rotations_[i + j]);
    A[j] = ExpQuaternion(B[j - 1] * d[j]);
    q = q * A[j];
  }
  if (d_R_d_ctrl == nullptr) return q.normalized();
  // R = R_i P_0 with P_j = A_{j+1} ... A_3 (P_3 = I).
  //  - R_i Exp(e) P_0 = R Exp(P_0^T e): d/de_i gets P_0^T.
  //  - A_j(d_j + dd) = A_j Exp(B_j Jr(B_j d_j) dd) moves R by
  //    Exp(P_j^T B_j Jr(B_j d_j) dd).
  //  - d_j = Log(R_{k}^T R_{k+1}) (k = i+j-1) moves by Jr^-1(d_j) e_{k+1}
  //    and, since Exp(-e) M = M Exp(-M^T e), by -Jr^-1(d_j) Exp(d_j)^T e_k.
  std::array<Eigen::Matrix3d, kOrder + 1> P;
  P[kOrder - 1] = Eigen::Matrix3d::Identity();
  for (int j = kOrder - 1; j >= 1; --j) {
    P[j - 1] = A[j].toRotationMatrix() * P[j];
  }
  std::array<Eigen::Matrix3d, kOrder>& J = *d_R_d_ctrl;
  J[0] = P[0].transpose();
  for (int k = 1; k < kOrder; ++k) J[k].setZero();
  for (int j = 1; j < kOrder; ++j) {
    const Eigen::Matrix3d through_d = P[j].transpose() * B[j - 1] *
                                      RightJacobian(B[j - 1] * d[j]) *
                                      RightJacobianInverse(d[j]);
    J[j] += through_d;
    J[j - 1] -= through_d * Exp(d[j]).transpose();
  }
  return q.normalized();
}

}  // namespace vio
