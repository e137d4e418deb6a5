#include "factors/marginalization_prior.h"

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>
#include <utility>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Quaterniond RotationOf(const double* x) {
  return Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(x + 3));
}

bool AllFinite(const double* x, int n) {
  return Eigen::Map<const Eigen::VectorXd>(x, n).allFinite();
}

}  // namespace

int PriorBlock::TangentSize() const {
  return kind == PriorBlockKind::kPose ? kPoseTangentSize : AmbientSize();
}

MarginalizationPrior::MarginalizationPrior(std::vector<PriorBlock> blocks,
                                           Eigen::MatrixXd jacobian,
                                           Eigen::VectorXd residual0,
                                           Eigen::MatrixXd information)
    : blocks_(std::move(blocks)),
      jacobian_(std::move(jacobian)),
      residual0_(std::move(residual0)) {
  if (blocks_.empty()) {
    throw std::invalid_argument("MarginalizationPrior: no parameter blocks");
  }
  int tangent_size = 0;
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const PriorBlock& block = blocks_[b];
    const std::string name = "MarginalizationPrior: block " + std::to_string(b);
    if (block.kind == PriorBlockKind::kPose &&
        block.AmbientSize() != kPoseAmbientSize) {
      throw std::invalid_argument(name + " is a pose but has " +
                                  std::to_string(block.AmbientSize()) +
                                  " values (expected 7)");
    }
    if (block.AmbientSize() < 1) {
      throw std::invalid_argument(name + " is empty");
    }
    if (!AllFinite(block.x0.data(), block.AmbientSize())) {
      throw std::invalid_argument(name + " has a non-finite x0");
    }
    tangent_offsets_.push_back(tangent_size);
    tangent_size += block.TangentSize();
    mutable_parameter_block_sizes()->push_back(block.AmbientSize());
  }
  if (jacobian_.cols() != tangent_size || jacobian_.rows() < 1 ||
      residual0_.size() != jacobian_.rows()) {
    throw std::invalid_argument(
        "MarginalizationPrior: J is " + std::to_string(jacobian_.rows()) +
        " x " + std::to_string(jacobian_.cols()) + " and r0 has " +
        std::to_string(residual0_.size()) + " rows, expected n x " +
        std::to_string(tangent_size) + " and n");
  }
  if (!jacobian_.allFinite() || !residual0_.allFinite()) {
    throw std::invalid_argument("MarginalizationPrior: J or r0 not finite");
  }
  set_num_residuals(static_cast<int>(jacobian_.rows()));
  if (information.size() == 0) {
    information_.setZero(tangent_size, tangent_size);
    information_.selfadjointView<Eigen::Lower>().rankUpdate(
        jacobian_.transpose());
    information_.triangularView<Eigen::StrictlyUpper>() =
        information_.transpose();
  } else if (information.rows() != tangent_size ||
             information.cols() != tangent_size || !information.allFinite()) {
    throw std::invalid_argument(
        "MarginalizationPrior: J^T J must be a finite " +
        std::to_string(tangent_size) + " x " + std::to_string(tangent_size) +
        " matrix");
  } else {
    information_ = std::move(information);
  }
  gradient0_ = jacobian_.transpose() * residual0_;
}

bool MarginalizationPrior::Delta(double const* const* parameters,
                                 Eigen::VectorXd* dx) const {
  dx->resize(jacobian_.cols());
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const PriorBlock& block = blocks_[b];
    const double* x = parameters[b];
    if (!AllFinite(x, block.AmbientSize())) return false;
    const int offset = tangent_offsets_[b];
    if (block.kind == PriorBlockKind::kPose) {
      // x (-) x0 = [t - t0, Log(q0^-1 (x) q)], PoseManifold's Minus.
      dx->segment<3>(offset + kPoseTranslation) =
          Eigen::Map<const Eigen::Vector3d>(x) -
          Eigen::Map<const Eigen::Vector3d>(block.x0.data());
      dx->segment<3>(offset + kPoseRotation) =
          Log(RotationOf(block.x0.data()).conjugate() * RotationOf(x));
    } else {
      dx->segment(offset, block.AmbientSize()) =
          Eigen::Map<const Eigen::VectorXd>(x, block.AmbientSize()) -
          Eigen::Map<const Eigen::VectorXd>(block.x0.data(),
                                            block.AmbientSize());
    }
  }
  return dx->allFinite();
}

void MarginalizationPrior::BlockJacobian(int b, const double* x,
                                         const Eigen::VectorXd& dx,
                                         double* jacobian) const {
  const PriorBlock& block = blocks_[b];
  const int offset = tangent_offsets_[b];
  const int rows = num_residuals();
  Eigen::Map<RowMajorMatrix> out(jacobian, rows, block.AmbientSize());
  if (block.kind == PriorBlockKind::kEuclidean) {
    // r is linear in x_b: d r / d x_b = J_b.
    out = jacobian_.middleCols(offset, block.AmbientSize());
    return;
  }
  // Pose. With x (+) d = [t + d_t, q Exp(d_theta)] and phi = Log(q0^-1 q):
  //   t (+) d_t - t0 = (t - t0) + d_t                       -> I
  //   Log(q0^-1 q Exp(d_theta)) = Log(Exp(phi) Exp(d_theta))
  //                             ~ phi + Jr^-1(phi) d_theta  -> Jr^-1(phi)
  // so d r / d d = [J_t, J_theta Jr^-1(phi)], and phi is the slot already in
  // dx. Lifted to the ambient space as LiftPoseJacobian does
  // (J_amb = J_tan * MinusJacobian(x)); written out here because that helper
  // needs a compile-time row count and the prior's is dynamic.
  Eigen::MatrixXd d_r_d_delta(rows, kPoseTangentSize);
  d_r_d_delta.leftCols<3>() =
      jacobian_.middleCols<3>(offset + kPoseTranslation);
  const Eigen::Vector3d phi = dx.segment<3>(offset + kPoseRotation);
  d_r_d_delta.rightCols<3>() = jacobian_.middleCols<3>(offset + kPoseRotation) *
                               RightJacobianInverse(phi);
  out = d_r_d_delta * PoseManifold::MinusJacobianAt(x);
}

bool MarginalizationPrior::Evaluate(double const* const* parameters,
                                    double* residuals,
                                    double** jacobians) const {
  Eigen::VectorXd dx;
  if (!Delta(parameters, &dx)) return false;
  Eigen::Map<Eigen::VectorXd> r(residuals, num_residuals());
  r = residual0_ + jacobian_ * dx;
  if (!r.allFinite()) return false;
  if (jacobians == nullptr) return true;
  for (size_t b = 0; b < blocks_.size(); ++b) {
    if (jacobians[b] == nullptr) continue;
    BlockJacobian(static_cast<int>(b), parameters[b], dx, jacobians[b]);
    if (!AllFinite(jacobians[b], num_residuals() * blocks_[b].AmbientSize())) {
      return false;
    }
  }
  return true;
}

}  // namespace vio
