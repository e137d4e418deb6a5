#ifndef VIO_FACTORS_MARGINALIZATION_PRIOR_H_
#define VIO_FACTORS_MARGINALIZATION_PRIOR_H_

// The Gaussian prior left behind when states are marginalised out of the
// sliding window (estimator/marginalization.h builds it).
//
// Residual (n rows, n = sum of the kept blocks' tangent sizes):
//   r(x) = r0 + J * dx,   dx = [x_1 (-) x0_1; ...; x_k (-) x0_k]
// where x0 is the linearisation point of the marginalisation, held fixed for
// the prior's lifetime (first-estimate Jacobians: the prior's J is never
// re-evaluated, so the information it carries stays consistent with the
// linearisation that produced it), and (-) is, per block:
//   pose / extrinsic (7 -> 6):  [t - t0,  Log(q0^-1 (x) q)]   (PoseManifold)
//   Euclidean (n -> n):         x - x0
// J (n x n) and r0 (n) come from the Schur complement of the marginalised
// problem: J^T J = H* and J^T r0 = -b*, so that 1/2 |r|^2 equals, up to a
// constant, the quadratic cost 1/2 dx^T H* dx - b*^T dx that the marginalised
// states leave on the kept ones (Sibley et al., "Sliding window filter with
// application to planetary landing", JFR 2010; Leutenegger et al.,
// "Keyframe-based visual-inertial odometry using nonlinear optimization",
// IJRR 2015).
//
// Parameter blocks: the kept blocks, in the order given at construction, each
// with its ambient size (7 for a pose, n for a Euclidean block of size n).
// Jacobians are with respect to the project's right perturbation
// (pose_manifold.h) and are returned in the ambient space through
// PoseManifold::MinusJacobianAt, like every other factor.

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <vector>

namespace vio {

// How the prior measures the distance of one kept block from its x0.
enum class PriorBlockKind {
  kPose,       // 7 -> 6 through PoseManifold's Minus (poses, extrinsics)
  kEuclidean,  // n -> n, plain subtraction (speed-bias, inverse depth, t_d)
};

// One kept parameter block of a prior: its kind and its linearisation point
// x0 (ambient values, copied when the prior is made).
struct PriorBlock {
  PriorBlockKind kind = PriorBlockKind::kEuclidean;
  std::vector<double> x0;

  int AmbientSize() const { return static_cast<int>(x0.size()); }
  int TangentSize() const;
};

class MarginalizationPrior final : public ceres::CostFunction {
 public:
  // jacobian: n x n' with n' = sum of the blocks' tangent sizes (columns in
  // block order) and any number of rows n >= 1; residual0: n.
  // information: J^T J when the caller has it (n' x n'; the marginalisation
  // does), empty to have it computed here.
  // Throws std::invalid_argument when the sizes disagree, a pose block does
  // not have 7 values, or any value is not finite. (By value: a caller done
  // with its matrices moves them in.)
  MarginalizationPrior(std::vector<PriorBlock> blocks, Eigen::MatrixXd jacobian,
                       Eigen::VectorXd residual0,
                       Eigen::MatrixXd information = Eigen::MatrixXd());

  // Never throws. Returns false when a parameter value, the residual or a
  // Jacobian entry is not finite.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<PriorBlock>& blocks() const { return blocks_; }
  const Eigen::MatrixXd& jacobian() const { return jacobian_; }
  const Eigen::VectorXd& residual0() const { return residual0_; }
  // J^T J and J^T r0, for a solver that forms the normal equations itself:
  // with dx = x (-) x0 and M = d dx / d (tangent perturbation), block
  // diagonal (I, or Jr^-1(phi) on a pose's rotation, see BlockJacobian),
  // the prior's Gauss-Newton terms are
  //   J_tan^T J_tan = M^T (J^T J) M,   J_tan^T r = M^T (J^T r0 + J^T J dx).
  const Eigen::MatrixXd& information() const { return information_; }
  const Eigen::VectorXd& gradient0() const { return gradient0_; }
  // The first tangent column of block b in J.
  int TangentOffset(int b) const { return tangent_offsets_[b]; }

  // Stacked x (-) x0 of all blocks (n' values); false when not finite.
  bool Delta(double const* const* parameters, Eigen::VectorXd* dx) const;

 private:
  // Writes the ambient Jacobian of block b (rows x ambient size, row-major).
  void BlockJacobian(int b, const double* x, const Eigen::VectorXd& dx,
                     double* jacobian) const;

  std::vector<PriorBlock> blocks_;
  std::vector<int> tangent_offsets_;  // first column of each block in J
  Eigen::MatrixXd jacobian_;          // J
  Eigen::VectorXd residual0_;         // r0
  Eigen::MatrixXd information_;       // J^T J
  Eigen::VectorXd gradient0_;         // J^T r0
};

}  // namespace vio

#endif  // VIO_FACTORS_MARGINALIZATION_PRIOR_H_
