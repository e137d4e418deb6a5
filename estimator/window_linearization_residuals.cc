// WindowLinearization's evaluation: each residual and its tangent Jacobians
// (lifted through the manifold's PlusJacobian unless the factor gives them in
// the tangent space), the marginalisation prior's normal equations, the
// robust loss applied as Ceres' Corrector does, and the cost of a candidate.

#include <algorithm>
#include <cmath>

#include "estimator/window_linearization.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstRowMajorMap = Eigen::Map<const RowMajorMatrix>;
using RowMajor26 = Eigen::Matrix<double, 2, 6, Eigen::RowMajor>;

}  // namespace

bool WindowLinearization::Linearize() {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.plus_offset < 0) continue;
    if (!(*blocks_in_)[i].manifold->PlusJacobian(
            (*blocks_in_)[i].values, plus_.data() + b.plus_offset)) {
      return false;
    }
  }
  double cost = 0.0;
  for (size_t k = 0; k < residuals_.size(); ++k) {
    if (!EvaluateResidual(static_cast<int>(k))) return false;
    Correct(static_cast<int>(k), &cost);
  }
  if (!std::isfinite(cost)) return false;
  cost_ = cost;
  BuildNormalEquations();
  return true;
}

bool WindowLinearization::EvaluateResidual(int k) {
  const Residual& res = residuals_[k];
  double* r = r_.data() + res.residual_offset;
  if (res.prior >= 0) {
    return (*residuals_in_)[k].cost->Evaluate(
               parameters_.data() + res.first_term, r, nullptr) &&
           LinearizePrior(k);
  }
  const TangentJacobians* tangent_cost = (*residuals_in_)[k].tangent;
  if (tangent_cost != nullptr) {
    for (int j = 0; j < res.num_terms; ++j) {
      const Term& t = terms_[res.first_term + j];
      ambient_ptrs_[j] = t.jacobian_offset < 0
                             ? nullptr
                             : jacobians_.data() + t.jacobian_offset;
    }
    if (!tangent_cost->EvaluateTangent(parameters_.data() + res.first_term, r,
                                       ambient_ptrs_.data())) {
      return false;
    }
    if (!Eigen::Map<const Eigen::VectorXd>(r, res.rows).allFinite()) {
      return false;
    }
    for (int j = 0; j < res.num_terms; ++j) {
      const Term& t = terms_[res.first_term + j];
      if (t.jacobian_offset >= 0 &&
          !ConstRowMajorMap(ambient_ptrs_[j], res.rows,
                            blocks_[t.block].tangent)
               .allFinite()) {
        return false;
      }
    }
    return true;
  }
  int ambient = 0;
  for (int j = 0; j < res.num_terms; ++j) {
    const Term& t = terms_[res.first_term + j];
    if (t.jacobian_offset < 0) {
      ambient_ptrs_[j] = nullptr;
      continue;
    }
    ambient_ptrs_[j] = ambient_.data() + ambient;
    ambient += res.rows * (*blocks_in_)[t.block].size;
  }
  if (!(*residuals_in_)[k].cost->Evaluate(parameters_.data() + res.first_term,
                                          r, ambient_ptrs_.data())) {
    return false;
  }
  if (!Eigen::Map<const Eigen::VectorXd>(r, res.rows).allFinite()) return false;
  for (int j = 0; j < res.num_terms; ++j) {
    const Term& t = terms_[res.first_term + j];
    if (t.jacobian_offset < 0) continue;
    const Block& b = blocks_[t.block];
    const int size = (*blocks_in_)[t.block].size;
    double* J = jacobians_.data() + t.jacobian_offset;
    Eigen::Map<RowMajorMatrix> tangent(J, res.rows, b.tangent);
    const ConstRowMajorMap amb(ambient_ptrs_[j], res.rows, size);
    if (b.plus_offset >= 0) {
      // Ceres' rule: the tangent Jacobian is J_ambient * PlusJacobian(x).
      const double* P = plus_.data() + b.plus_offset;
      if (res.rows == 2 && size == kPoseAmbientSize &&
          b.tangent == kPoseTangentSize) {
        Eigen::Map<RowMajor26>(J).noalias() =
            Eigen::Map<const Eigen::Matrix<double, 2, 7, Eigen::RowMajor>>(
                ambient_ptrs_[j]) *
            Eigen::Map<const PosePlusJacobian>(P);
      } else {
        tangent.noalias() =
            amb.lazyProduct(ConstRowMajorMap(P, size, b.tangent));
      }
    } else {
      tangent = amb;
    }
    if (!tangent.allFinite()) return false;
  }
  return true;
}

bool WindowLinearization::LinearizePrior(int k) {
  const Residual& res = residuals_[k];
  Prior& p = priors_[res.prior];
  const MarginalizationPrior& f = *p.factor;
  if (!Eigen::Map<const Eigen::VectorXd>(r_.data() + res.residual_offset,
                                         res.rows)
           .allFinite() ||
      !f.Delta(parameters_.data() + res.first_term, &p.delta)) {
    return false;
  }
  // M: identity but for Jr^-1(phi) on each pose's rotation (the prior's
  // BlockJacobian); M^T G M and M^T (J^T r0 + G dx) touch only those columns.
  p.information = f.information();
  p.gradient = f.gradient0();
  p.gradient.noalias() += f.information() * p.delta;
  for (size_t b = 0; b < p.blocks.size(); ++b) {
    if (f.blocks()[b].kind != PriorBlockKind::kPose) continue;
    const int c = f.TangentOffset(static_cast<int>(b)) + kPoseRotation;
    const Eigen::Matrix3d M = RightJacobianInverse(p.delta.segment<3>(c));
    p.information.middleCols<3>(c) = p.information.middleCols<3>(c) * M;
    p.information.middleRows<3>(c) =
        M.transpose() * p.information.middleRows<3>(c);
    p.gradient.segment<3>(c) = M.transpose() * p.gradient.segment<3>(c);
  }
  return p.information.allFinite() && p.gradient.allFinite();
}

void WindowLinearization::Correct(int k, double* cost) {
  const Residual& res = residuals_[k];
  const ceres::LossFunction* loss = (*residuals_in_)[k].loss;
  Eigen::Map<Eigen::VectorXd> r(r_.data() + res.residual_offset, res.rows);
  const double sq = r.squaredNorm();
  if (loss == nullptr) {
    *cost += 0.5 * sq;
    return;
  }
  double rho[3];
  loss->Evaluate(sq, rho);
  *cost += 0.5 * rho[0];
  // Ceres' Corrector (internal/ceres/corrector.cc): the robust problem's
  // Gauss-Newton model is that of r~ = s r, J~ = sqrt(rho') (I - a r r^T /
  // |r|^2) J with a the root of a^2/2 - a = rho'' |r|^2 / rho' (Triggs et
  // al., "Bundle adjustment - a modern synthesis", sec. 4.3); where rho'' <= 0
  // (Huber and Cauchy away from the origin) a = 0, plain sqrt(rho') scaling.
  double scale_r = 0.0;
  double scale_j = 0.0;
  double alpha_sq_norm = 0.0;
  if (rho[1] > 0.0) {
    scale_j = std::sqrt(rho[1]);
    scale_r = scale_j;
    if (sq > 0.0 && rho[2] > 0.0) {
      const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * sq * rho[2] / rho[1]);
      scale_r = scale_j / (1.0 - alpha);
      alpha_sq_norm = alpha / sq;
    }
  }
  for (int j = res.first_term; j < res.first_term + res.num_terms; ++j) {
    const Term& t = terms_[j];
    if (t.jacobian_offset < 0) continue;
    Eigen::Map<RowMajorMatrix> J(jacobians_.data() + t.jacobian_offset,
                                 res.rows, blocks_[t.block].tangent);
    if (alpha_sq_norm != 0.0) {
      const Eigen::RowVectorXd rtJ = r.transpose() * J;
      J -= alpha_sq_norm * r * rtJ;
    }
    J *= scale_j;
  }
  r *= scale_r;
}

bool WindowLinearization::CandidateCost(const Eigen::VectorXd& dx,
                                        double* cost) {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.role == Role::kConstant) continue;
    const WindowSolverBlock& in = (*blocks_in_)[i];
    double* out = candidate_.data() + b.state_offset;
    if (in.manifold != nullptr) {
      if (!in.manifold->Plus(in.values, dx.data() + b.offset, out)) {
        return false;
      }
      continue;
    }
    for (int c = 0; c < in.size; ++c) {
      // Projected onto the bounds, as Ceres' ParameterBlock::Plus does.
      out[c] = std::min(std::max(in.values[c] + dx[b.offset + c], in.lower),
                        in.upper);
    }
  }
  double sum = 0.0;
  for (size_t k = 0; k < residuals_.size(); ++k) {
    const Residual& res = residuals_[k];
    if (!(*residuals_in_)[k].cost->Evaluate(candidates_.data() + res.first_term,
                                            scratch_r_.data(), nullptr)) {
      return false;
    }
    const Eigen::Map<const Eigen::VectorXd> r(scratch_r_.data(), res.rows);
    if (!r.allFinite()) return false;
    const double sq = r.squaredNorm();
    if ((*residuals_in_)[k].loss == nullptr) {
      sum += 0.5 * sq;
    } else {
      double rho[3];
      (*residuals_in_)[k].loss->Evaluate(sq, rho);
      sum += 0.5 * rho[0];
    }
  }
  if (!std::isfinite(sum)) return false;
  *cost = sum;
  return true;
}

}  // namespace vio
