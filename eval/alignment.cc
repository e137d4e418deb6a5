#include "eval/alignment.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>
#include <string>

#include "eval/eval_error.h"

namespace vio {
namespace {

// Below this ratio of singular values (or of spread to cross-covariance) the
// point sets are treated as degenerate: the optimal rotation is not unique.
constexpr double kDegenerateRatio = 1e-10;

using Points = Eigen::Matrix<double, 3, Eigen::Dynamic>;

Points PositionsOf(const Trajectory& trajectory) {
  Points points(3, static_cast<Eigen::Index>(trajectory.size()));
  for (size_t i = 0; i < trajectory.size(); ++i) {
    points.col(static_cast<Eigen::Index>(i)) = trajectory[i].p_w_b;
  }
  return points;
}

[[noreturn]] void Degenerate(AlignmentMode mode, const std::string& why) {
  throw EvalError(std::string(AlignmentModeName(mode)) +
                  " alignment is degenerate: " + why);
}

// Umeyama's rotation is unique only when the cross-covariance
// Sigma_xy = 1/n sum (y_i - y_mean)(x_i - x_mean)^T has rank >= 2, i.e. the
// points are not all on one line (evo checks the same condition).
void CheckNotCollinear(const Points& p_e, const Points& p_w,
                       AlignmentMode mode) {
  const Points x = p_e.colwise() - p_e.rowwise().mean();
  const Points y = p_w.colwise() - p_w.rowwise().mean();
  const Eigen::Matrix3d sigma = y * x.transpose();
  const Eigen::Vector3d d =
      Eigen::JacobiSVD<Eigen::Matrix3d>(sigma).singularValues();
  if (!(d(0) > 0.0) || d(1) <= kDegenerateRatio * d(0)) {
    Degenerate(mode, "the associated positions are (nearly) collinear");
  }
}

// Eigen::umeyama is Umeyama's eqs. 34-43 exactly as evo implements them (the
// same centring, 1/n covariance, reflection guard S and scale
// c = tr(D S) / sigma_x^2); it returns [c R, t; 0, 1].
Alignment AlignUmeyama(const Points& p_e, const Points& p_w,
                       AlignmentMode mode) {
  CheckNotCollinear(p_e, p_w, mode);
  const bool with_scale = mode == AlignmentMode::kSim3;
  const Eigen::Matrix4d T = Eigen::umeyama(p_e, p_w, with_scale);
  Alignment a;
  a.mode = mode;
  a.scale = with_scale ? T.block<3, 1>(0, 0).norm() : 1.0;
  a.R_w_e = T.topLeftCorner<3, 3>() / a.scale;
  a.t_w_e = T.topRightCorner<3, 1>();
  return a;
}

// posyaw: minimise J(theta, t) = sum_i |y_i - Rz(theta) x_i - t|^2.
//   dJ/dt = 0  =>  t = y_mean - Rz x_mean, and with x' = x - x_mean,
//   y' = y - y_mean:  J = const - 2 sum_i y'_i^T Rz x'_i.
//   Rz leaves z alone, so y'^T Rz x' = y'_z x'_z + y'_xy^T R2(theta) x'_xy,
//   and with H = sum_i y'_xy,i x'_xy,i^T (the 2x2 xy cross-covariance):
//   sum_i y'_xy^T R2 x'_xy = cos(theta) (H00 + H11) + sin(theta) (H10 - H01)
//                          = A cos(theta) + B sin(theta),
//   maximal at theta = atan2(B, A), unique unless A = B = 0.
// A static ground truth: the yaw of each q_gt * q_est^-1 (a rotation about z
// when both attitudes share the gravity direction), averaged on the circle
// so that angles near +-pi do not cancel.
double YawFromOrientations(const Trajectory& estimate,
                           const Trajectory& ground_truth) {
  double sum_sin = 0.0, sum_cos = 0.0;
  for (size_t i = 0; i < estimate.size(); ++i) {
    const Eigen::Matrix3d M =
        (ground_truth[i].q_w_b * estimate[i].q_w_b.conjugate())
            .toRotationMatrix();
    const double yaw = std::atan2(M(1, 0), M(0, 0));
    sum_sin += std::sin(yaw);
    sum_cos += std::cos(yaw);
  }
  return std::atan2(sum_sin, sum_cos);
}

Alignment AlignPosYaw(const Points& p_e, const Points& p_w,
                      const Trajectory& estimate,
                      const Trajectory& ground_truth) {
  const Eigen::Vector3d x_mean = p_e.rowwise().mean();
  const Eigen::Vector3d y_mean = p_w.rowwise().mean();
  const Points x = p_e.colwise() - x_mean;
  const Points y = p_w.colwise() - y_mean;
  const double gt_spread =
      std::sqrt(y.topRows<2>().squaredNorm() / static_cast<double>(y.cols()));
  if (gt_spread < kPosYawMinSpread) {
    Alignment a;
    a.mode = AlignmentMode::kPosYaw;
    a.yaw_from_orientations = true;
    a.R_w_e = Eigen::AngleAxisd(YawFromOrientations(estimate, ground_truth),
                                Eigen::Vector3d::UnitZ())
                  .matrix();
    a.t_w_e = y_mean - a.R_w_e * x_mean;
    return a;
  }
  const Eigen::Matrix2d H = y.topRows<2>() * x.topRows<2>().transpose();
  const double A = H(0, 0) + H(1, 1);
  const double B = H(1, 0) - H(0, 1);
  const double spread =
      std::sqrt(x.topRows<2>().squaredNorm() * y.topRows<2>().squaredNorm());
  if (!(spread > 0.0) || std::hypot(A, B) <= kDegenerateRatio * spread) {
    Degenerate(AlignmentMode::kPosYaw,
               "the associated positions do not spread in x-y");
  }
  Alignment a;
  a.mode = AlignmentMode::kPosYaw;
  a.R_w_e =
      Eigen::AngleAxisd(std::atan2(B, A), Eigen::Vector3d::UnitZ()).matrix();
  a.t_w_e = y_mean - a.R_w_e * x_mean;
  return a;
}

}  // namespace

AlignmentMode ParseAlignmentMode(const std::string& name) {
  if (name == "none") return AlignmentMode::kNone;
  if (name == "se3") return AlignmentMode::kSe3;
  if (name == "sim3") return AlignmentMode::kSim3;
  if (name == "posyaw") return AlignmentMode::kPosYaw;
  throw std::invalid_argument("unknown alignment '" + name +
                              "' (expected se3, sim3, posyaw or none)");
}

const char* AlignmentModeName(AlignmentMode mode) {
  switch (mode) {
    case AlignmentMode::kNone:
      return "none";
    case AlignmentMode::kSe3:
      return "se3";
    case AlignmentMode::kSim3:
      return "sim3";
    case AlignmentMode::kPosYaw:
      return "posyaw";
  }
  return "unknown";
}

size_t MinimumPoses(AlignmentMode mode) {
  switch (mode) {
    case AlignmentMode::kNone:
      return 1;
    case AlignmentMode::kPosYaw:
      return 2;
    case AlignmentMode::kSe3:
    case AlignmentMode::kSim3:
      return 3;
  }
  return 3;
}

StampedPose Alignment::Apply(const StampedPose& pose_e) const {
  StampedPose pose_w;
  pose_w.t_ns = pose_e.t_ns;
  pose_w.p_w_b = scale * (R_w_e * pose_e.p_w_b) + t_w_e;
  pose_w.q_w_b = Eigen::Quaterniond(R_w_e) * pose_e.q_w_b;
  pose_w.q_w_b.normalize();
  return pose_w;
}

Trajectory Alignment::Apply(const Trajectory& trajectory_e) const {
  Trajectory out;
  out.reserve(trajectory_e.size());
  for (const StampedPose& p : trajectory_e) out.push_back(Apply(p));
  return out;
}

Alignment Align(const Trajectory& estimate, const Trajectory& ground_truth,
                AlignmentMode mode) {
  if (estimate.size() != ground_truth.size()) {
    throw std::invalid_argument("Align: the trajectories are not associated (" +
                                std::to_string(estimate.size()) + " vs " +
                                std::to_string(ground_truth.size()) +
                                " poses)");
  }
  if (estimate.size() < MinimumPoses(mode)) {
    throw EvalError(
        std::string(AlignmentModeName(mode)) + " alignment needs at least " +
        std::to_string(MinimumPoses(mode)) + " associated poses (got " +
        std::to_string(estimate.size()) + ")");
  }
  const Points p_e = PositionsOf(estimate);
  const Points p_w = PositionsOf(ground_truth);
  switch (mode) {
    case AlignmentMode::kNone:
      return Alignment{};
    case AlignmentMode::kPosYaw:
      return AlignPosYaw(p_e, p_w, estimate, ground_truth);
    case AlignmentMode::kSe3:
    case AlignmentMode::kSim3:
      return AlignUmeyama(p_e, p_w, mode);
  }
  return Alignment{};
}

}  // namespace vio
