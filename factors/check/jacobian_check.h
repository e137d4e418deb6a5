#ifndef VIO_FACTORS_CHECK_JACOBIAN_CHECK_H_
#define VIO_FACTORS_CHECK_JACOBIAN_CHECK_H_

// Numeric proof of a factor's analytic Jacobians, in the tangent space.
//
// For each parameter block with manifold M (Euclidean when null):
//   analytic  J_a = J_ambient(x) * M.PlusJacobian(x)       (what Ceres uses)
//   numeric   J_n[:, k] = (r(x (+) h e_k) - r(x (+) -h e_k)) / (2 h)
// where (+) is M.Plus, so a wrong PlusJacobian is caught as surely as a wrong
// factor Jacobian. (ceres::GradientChecker differentiates in the ambient space
// and maps with PlusJacobian, which cannot catch the former; the unit tests use
// it as a second opinion.) The errors reported per block are
//   max_abs_error = max |J_a - J_n|,
//   max_rel_error = max |J_a - J_n| / max(max |J_n|, kMinScale),
// i.e. relative to the block's largest entry, which keeps near-zero entries
// from inflating it. A factor that also gives its Jacobians directly in the
// tangent space (factors/tangent_jacobians.h) gets a second entry per block,
// "<block> (tangent)": its EvaluateTangent Jacobian against the same J_n.
//
// The random but realistic states of each factor are made by its "case"
// (factors/check/factor_cases.h); the jacobian_check tool and the factors'
// tests share them.

#include <ceres/cost_function.h>
#include <ceres/manifold.h>

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace vio {

// A cost function together with one linearisation point.
struct FactorInstance {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<std::vector<double>> blocks;  // parameter values, one per block
  // One per block; nullptr means Euclidean.
  std::vector<std::shared_ptr<const ceres::Manifold>> manifolds;
  std::vector<std::string> block_names;  // e.g. "pose_i", "speed_bias_j"
};

struct BlockJacobianError {
  std::string block;
  double max_abs_error = 0.0;
  double max_rel_error = 0.0;
};

struct JacobianCheckOptions {
  double step = 1e-6;       // central-difference step in the tangent space
  double min_scale = 1e-9;  // floor of the relative error's denominator
};

// Evaluates the instance analytically and numerically and returns one error
// entry per parameter block (two for a TangentJacobians factor, see above).
// Returns false (and leaves *errors empty) when the cost function's Evaluate
// (or EvaluateTangent) fails at the point or at a perturbed point.
bool CompareJacobians(const FactorInstance& instance,
                      const JacobianCheckOptions& options,
                      std::vector<BlockJacobianError>* errors);

// A factor the check knows: a name (the tool's --factor value), a line of
// description, the tolerance its Jacobians must meet, and a sampler of random
// realistic instances.
struct FactorCase {
  std::string name;
  std::string description;
  double tolerance = 1e-5;  // on max_rel_error
  std::function<FactorInstance(std::mt19937& rng)> sample;
};

}  // namespace vio

#endif  // VIO_FACTORS_CHECK_JACOBIAN_CHECK_H_
