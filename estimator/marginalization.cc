#include "estimator/marginalization.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>

#include "estimator/marginalization_system.h"
#include "estimator/null_space_floor.h"
#include "factors/pose_manifold.h"

namespace vio {
namespace {

MarginalizationResult Refusal(std::string message) {
  MarginalizationResult result;
  result.status = MarginalizationStatus::kFailed;
  result.message = std::move(message);
  return result;
}

// Checks the problem's structure and values; returns "" when it is valid.
std::string CheckProblem(const MarginalizationProblem& problem) {
  // values -> ambient size (names are built only for an error message)
  std::unordered_map<const double*, int> listed;
  listed.reserve(2 * problem.parameter_blocks.size());
  for (size_t i = 0; i < problem.parameter_blocks.size(); ++i) {
    const MarginalizationParameterBlock& p = problem.parameter_blocks[i];
    auto name = [i] { return "parameter block " + std::to_string(i); };
    if (p.values == nullptr || p.size < 1) return name() + " is empty";
    if (!listed.emplace(p.values, p.size).second) {
      return name() + " is listed twice";
    }
    if (p.manifold && p.manifold->AmbientSize() != p.size) {
      return name() + " has a manifold of another ambient size";
    }
    if (!Eigen::Map<const Eigen::VectorXd>(p.values, p.size).allFinite()) {
      return name() + " has a non-finite value";
    }
  }
  for (size_t i = 0; i < problem.marginalized.size(); ++i) {
    if (listed.count(problem.marginalized[i]) == 0) {
      return "marginalised block " + std::to_string(i) + " is not listed";
    }
  }
  for (size_t i = 0; i < problem.residual_blocks.size(); ++i) {
    const MarginalizationResidualBlock& r = problem.residual_blocks[i];
    auto name = [i] { return "residual block " + std::to_string(i); };
    if (r.cost == nullptr) return name() + " has no cost function";
    if (r.cost->parameter_block_sizes().size() != r.parameter_blocks.size()) {
      return name() + " has the wrong number of parameter blocks";
    }
    if (r.cost->num_residuals() < 1) return name() + " has no residuals";
    for (size_t j = 0; j < r.parameter_blocks.size(); ++j) {
      const auto it = listed.find(r.parameter_blocks[j]);
      if (it == listed.end()) return name() + " touches an unlisted block";
      if (it->second != r.cost->parameter_block_sizes()[j]) {
        return name() + ": parameter " + std::to_string(j) +
               " has a size other than the listed block's";
      }
    }
  }
  return "";
}

// The kept blocks' coordinates in H* (tangent sizes, in order).
std::vector<CoordinateBlock> KeptCoordinateBlocks(
    const std::vector<const MarginalizationParameterBlock*>& kept) {
  std::vector<CoordinateBlock> blocks;
  int offset = 0;
  for (const MarginalizationParameterBlock* p : kept) {
    blocks.push_back({offset, p->TangentSize()});
    offset += p->TangentSize();
  }
  return blocks;
}

// Pseudo-inverse of the symmetric H_mm by eigen-decomposition; eigenvalues
// below floor * max count as zero. Returns the number of dropped directions.
int PseudoInverse(const Eigen::MatrixXd& H_mm, double floor,
                  Eigen::MatrixXd* inverse) {
  if (H_mm.rows() == 0) {  // nothing marginalised: H* = H_kk
    inverse->resize(0, 0);
    return 0;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      0.5 * (H_mm + H_mm.transpose()));
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const double threshold = floor * std::max(lambda.maxCoeff(), 0.0);
  Eigen::VectorXd lambda_inv(lambda.size());
  int dropped = 0;
  for (int i = 0; i < lambda.size(); ++i) {
    const bool informative = lambda[i] > threshold && lambda[i] > 0.0;
    lambda_inv[i] = informative ? 1.0 / lambda[i] : 0.0;
    dropped += informative ? 0 : 1;
  }
  *inverse = eig.eigenvectors() * lambda_inv.asDiagonal() *
             eig.eigenvectors().transpose();
  return dropped;
}

// H* = H_kk - H_km H_mm^+ H_mk (symmetrised) and b* = b_k - H_km H_mm^+ b_m
// for H, b ordered [marginalised (m_size) | kept]. Returns the rank
// deficiency of H_mm.
int SchurComplement(const Eigen::MatrixXd& H, const Eigen::VectorXd& b,
                    int m_size, double floor, Eigen::MatrixXd* H_star,
                    Eigen::VectorXd* b_star) {
  const int k_size = static_cast<int>(H.rows()) - m_size;
  Eigen::MatrixXd H_mm_inv;
  const int deficiency =
      PseudoInverse(H.topLeftCorner(m_size, m_size), floor, &H_mm_inv);
  const Eigen::MatrixXd H_km_H_mm_inv =
      H.bottomLeftCorner(k_size, m_size) * H_mm_inv;
  *H_star = H.bottomRightCorner(k_size, k_size) -
            H_km_H_mm_inv * H.topRightCorner(m_size, k_size);
  *H_star = 0.5 * (*H_star + H_star->transpose());
  *b_star = b.tail(k_size) - H_km_H_mm_inv * b.head(m_size);
  return deficiency;
}

// A square root J of H* and r0 = -J^-T b*, so that J^T J = H* and
// J^T r0 = -b*. Where H* is positive definite with no Cholesky pivot below
// floor times the largest (the estimator's case: the gauge is held by the
// prior carried from the start): J = L^T of H* = L L^T, r0 = -L^-1 b*, a
// triangular solve. Otherwise: H* = V S V^T with S floored at floor * max(S),
// J = sqrt(S) V^T and r0 = -sqrt(S)^-1 V^T b* (V orthonormal). Returns the
// number of floored eigenvalues (0 on the Cholesky path), or -1 when H* holds
// no information at all (largest eigenvalue not > 0) or cannot be decomposed.
// When the floored eigenvectors each lie in one kept block (`blocks`: world
// points, null_space_floor.h), or are exact zeros, the floored
// H_f = V max(S, s_min) V^T is found without the eigenvectors, by
// FloorBlockDirections or else FloorNullSpace, and J = L^T of H_f = L L^T,
// r0 = -L^-1 b*: the same J^T J, J^T r0 and |r0|^2 (to rounding);
// *floored_information then receives H_f (= J^T J), else is emptied. *path
// says which way J was found.
int SquareRoot(const Eigen::MatrixXd& H_star, const Eigen::VectorXd& b_star,
               double floor, const std::vector<CoordinateBlock>& blocks,
               Eigen::MatrixXd* J, Eigen::VectorXd* r0,
               Eigen::MatrixXd* floored_information, PriorSquareRoot* path) {
  floored_information->resize(0, 0);
  // A factor usable unfloored: every pivot^2 positive and at least floor
  // times the largest.
  auto usable = [floor](const Eigen::LLT<Eigen::MatrixXd>& llt) {
    if (llt.info() != Eigen::Success) return false;
    const Eigen::VectorXd pivots = llt.matrixLLT().diagonal().cwiseAbs2();
    return pivots.minCoeff() > 0.0 &&
           pivots.minCoeff() >= floor * pivots.maxCoeff();
  };
  const Eigen::LLT<Eigen::MatrixXd> llt(H_star);
  if (usable(llt)) {
    *J = llt.matrixU();
    *r0 = -llt.matrixL().solve(b_star);
    *path = PriorSquareRoot::kCholesky;
    return 0;
  }
  Eigen::MatrixXd H_f;
  int null_floored = 0;
  for (const PriorSquareRoot way :
       {PriorSquareRoot::kBlockFloor, PriorSquareRoot::kNullSpaceFloor}) {
    const bool found =
        way == PriorSquareRoot::kBlockFloor
            ? FloorBlockDirections(H_star, floor, blocks, &H_f, &null_floored)
            : FloorNullSpace(H_star, floor, &H_f, &null_floored);
    if (!found) continue;
    // The block floor's H_f is held to H*'s own test (null_space_floor.h,
    // (b)); the subspace floor has checked its spectrum already.
    const Eigen::LLT<Eigen::MatrixXd> llt_f(H_f);
    if (way == PriorSquareRoot::kBlockFloor ? !usable(llt_f)
                                            : llt_f.info() != Eigen::Success) {
      continue;
    }
    *J = llt_f.matrixU();
    *r0 = -llt_f.matrixL().solve(b_star);
    *floored_information = std::move(H_f);
    *path = way;
    return null_floored;
  }
  *path = PriorSquareRoot::kEigen;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H_star);
  if (eig.info() != Eigen::Success) return -1;
  const double lambda_max = eig.eigenvalues().maxCoeff();
  if (!(lambda_max > 0.0)) return -1;
  Eigen::VectorXd s = eig.eigenvalues();
  // The floor is relative but never below the smallest normal double, so
  // that 1 / sqrt(s) stays finite.
  const double s_min =
      std::max(floor * lambda_max, std::numeric_limits<double>::min());
  int floored = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (s[i] < s_min) {
      s[i] = s_min;
      ++floored;
    }
  }
  const Eigen::VectorXd sqrt_s = s.cwiseSqrt();
  *J = sqrt_s.asDiagonal() * eig.eigenvectors().transpose();
  *r0 = -(sqrt_s.cwiseInverse().asDiagonal() *
          (eig.eigenvectors().transpose() * b_star));
  return floored;
}

}  // namespace

bool MarginalizationOptions::Validate(std::string* message) const {
  for (double floor : {marginalized_eigenvalue_floor, prior_eigenvalue_floor}) {
    if (!(floor >= 0.0 && floor < 1.0)) {
      *message = "eigenvalue floors must be in [0, 1) (got " +
                 std::to_string(floor) + ")";
      return false;
    }
  }
  return true;
}

MarginalizationResult Marginalize(const MarginalizationProblem& problem,
                                  const MarginalizationOptions& options) {
  std::string error;
  if (!options.Validate(&error)) return Refusal(error);
  error = CheckProblem(problem);
  if (!error.empty()) return Refusal(error);

  MarginalizationSystem system(problem);
  if (system.kept_size() == 0) return Refusal("no block is kept");
  const std::vector<const MarginalizationParameterBlock*>& kept = system.kept();
  for (const MarginalizationParameterBlock* p : kept) {
    if (p->manifold != nullptr &&
        dynamic_cast<const PoseManifold*>(p->manifold) == nullptr) {
      return Refusal("parameter block " +
                     std::to_string(p - problem.parameter_blocks.data()) +
                     " is kept but has a manifold other than PoseManifold");
    }
  }

  MarginalizationResult result;
  // A failure after evaluation keeps the counters (they say why).
  auto fail = [&result](const std::string& message) {
    result.status = MarginalizationStatus::kFailed;
    result.message = message;
    result.jacobian.resize(0, 0);
    result.residual0.resize(0);
    return result;
  };
  system.Accumulate(&result.num_residual_blocks_used,
                    &result.num_skipped_residual_blocks);
  const int scalars_dropped =
      system.EliminateScalars(options.marginalized_eigenvalue_floor);

  Eigen::MatrixXd H_star;
  Eigen::VectorXd b_star;
  result.marginalized_rank_deficiency =
      scalars_dropped +
      SchurComplement(system.H(), system.b(), system.dense_marginalized_size(),
                      options.marginalized_eigenvalue_floor, &H_star, &b_star);
  if (!H_star.allFinite() || !b_star.allFinite()) {
    return fail("the Schur complement is not finite");
  }
  result.num_floored_eigenvalues = SquareRoot(
      H_star, b_star, options.prior_eigenvalue_floor,
      KeptCoordinateBlocks(kept), &result.jacobian, &result.residual0,
      &result.floored_information, &result.square_root);
  if (result.num_floored_eigenvalues < 0) {
    return fail("no information is left on the kept blocks (" +
                std::to_string(result.num_skipped_residual_blocks) +
                " residual blocks skipped)");
  }
  if (!result.jacobian.allFinite() || !result.residual0.allFinite()) {
    return fail("the prior's J or r0 is not finite");
  }
  result.information = std::move(H_star);
  result.gradient = -b_star;
  for (const MarginalizationParameterBlock* p : kept) {
    result.kept_parameter_blocks.push_back(p->values);
    result.kept_blocks.push_back(
        {p->manifold ? PriorBlockKind::kPose : PriorBlockKind::kEuclidean,
         std::vector<double>(p->values, p->values + p->size)});
  }
  const bool degenerate = result.num_skipped_residual_blocks > 0 ||
                          result.marginalized_rank_deficiency > 0;
  result.status = degenerate ? MarginalizationStatus::kDegenerate
                             : MarginalizationStatus::kOk;
  if (degenerate) {
    result.message = std::to_string(result.num_skipped_residual_blocks) +
                     " residual blocks skipped, H_mm rank deficient by " +
                     std::to_string(result.marginalized_rank_deficiency);
  }
  return result;
}

std::unique_ptr<MarginalizationPrior> MarginalizationResult::MakePrior()
    const& {
  // Without floored eigenvalues J^T J is H* (to rounding), with them it is
  // floored_information when the square root was taken from it: the prior
  // need not form it again.
  return std::make_unique<MarginalizationPrior>(
      kept_blocks, jacobian, residual0,
      num_floored_eigenvalues == 0 ? information : floored_information);
}

std::unique_ptr<MarginalizationPrior> MarginalizationResult::MakePrior() && {
  Eigen::MatrixXd& J_T_J =
      num_floored_eigenvalues == 0 ? information : floored_information;
  return std::make_unique<MarginalizationPrior>(
      kept_blocks, std::move(jacobian), std::move(residual0), std::move(J_T_J));
}

MarginalizationResidualBlock PriorResidualBlock(
    const MarginalizationResult& result, const MarginalizationPrior* prior) {
  return {prior, nullptr, result.kept_parameter_blocks};
}

std::vector<MarginalizationParameterBlock> KeptParameterBlocks(
    const MarginalizationResult& result, const ceres::Manifold* pose_manifold) {
  std::vector<MarginalizationParameterBlock> blocks;
  for (size_t i = 0; i < result.kept_blocks.size(); ++i) {
    const PriorBlock& kb = result.kept_blocks[i];
    blocks.push_back(
        {result.kept_parameter_blocks[i], kb.AmbientSize(),
         kb.kind == PriorBlockKind::kPose ? pose_manifold : nullptr, false});
  }
  return blocks;
}

}  // namespace vio
