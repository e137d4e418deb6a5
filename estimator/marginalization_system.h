#ifndef VIO_ESTIMATOR_MARGINALIZATION_SYSTEM_H_
#define VIO_ESTIMATOR_MARGINALIZATION_SYSTEM_H_

// The linearised system of one marginalisation step (marginalization.h):
// every residual block evaluated at the current values into
//   H = sum J~^T J~,   b = -sum J~^T r~      (tangent space, robust-scaled)
// over the blocks it touches. Two kinds of marginalised blocks:
//   - scalars: Euclidean, size 1, no residual block touching two of them
//     (the inverse depths of the landmarks leaving with the oldest frame).
//     Their rows of H are a diagonal entry h_s and a sparse row w_s, so
//     they are eliminated in closed form, one rank-one update each:
//        H_dd -= w_s w_s^T / h_s,   b_d -= w_s b_s / h_s;
//   - the others (the oldest pose and speed-bias) stay in a dense system
//     ordered [marginalised | kept], which marginalization.cc reduces.
// Eliminating the scalars first is the same Schur complement as eliminating
// all marginalised blocks at once (block elimination), at a fraction of the
// cost: the dense system is 15 + 150 wide instead of 15 + 60 + 150, and the
// scalars' updates touch only the poses that saw them.
//
// Residual blocks are evaluated as the window solver does: a
// MarginalizationPrior through its stored J^T J, a factor with
// TangentJacobians through them, any other through J_ambient *
// PlusJacobian.

#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "estimator/marginalization.h"

namespace vio {

class MarginalizationSystem {
 public:
  // problem must have passed the structural checks of Marginalize and must
  // outlive this object.
  explicit MarginalizationSystem(const MarginalizationProblem& problem);

  // Tangent size of the marginalised blocks kept in the dense system, and of
  // the kept blocks; the dense system is [marginalised | kept].
  int dense_marginalized_size() const { return dense_marginalized_size_; }
  int kept_size() const { return kept_size_; }
  // The kept blocks, in listing order.
  const std::vector<const MarginalizationParameterBlock*>& kept() const {
    return kept_;
  }

  // Evaluates every residual block and adds it. A block whose Evaluate
  // fails, whose residual or Jacobian is not finite or whose loss gives a
  // non-finite or negative rho' is left out and counted in *skipped.
  void Accumulate(int* used, int* skipped);

  // Eliminates the scalar blocks. One whose h_s is not above floor times the
  // largest diagonal entry of the marginalised part of H carries no
  // information: it is dropped (no update). Returns the number dropped.
  int EliminateScalars(double floor);

  // The dense system after EliminateScalars (both triangles filled).
  const Eigen::MatrixXd& H() const { return H_; }
  const Eigen::VectorXd& b() const { return b_; }

 private:
  enum class Role { kDense, kScalar };
  struct Slot {
    const MarginalizationParameterBlock* block = nullptr;
    Role role = Role::kDense;
    int offset = 0;  // dense: first column; scalar: index into scalars_
  };
  struct Scalar {
    double h = 0.0;            // sum J_s^T J_s
    double b = 0.0;            // -sum J_s^T r
    std::vector<int> touched;  // dense slots' offsets its residuals touch
    std::vector<int> tangent;  // their tangent sizes
    int w_offset = 0;          // into w_
    int w_size = 0;
  };

  void AssignSlots();
  void LayOutScalars();
  // Evaluates residual block k into residual_ and tangent_ (robust-scaled);
  // false when it cannot be used.
  bool Evaluate(int k);
  bool AccumulatePrior(int k);
  void Add(int k);

  const MarginalizationProblem& problem_;
  std::unordered_map<const double*, Slot> slots_;
  std::vector<const MarginalizationParameterBlock*> kept_;
  std::vector<Scalar> scalars_;
  int dense_marginalized_size_ = 0;
  int kept_size_ = 0;

  Eigen::MatrixXd H_;  // dense [marginalised | kept]; upper until eliminated
  Eigen::VectorXd b_;
  std::vector<double> w_;  // every scalar's row, packed

  // Scratch for one residual block.
  Eigen::VectorXd residual_;
  std::vector<double> ambient_;
  std::vector<double> tangent_;
  std::vector<double*> ambient_ptrs_;
  std::vector<int> tangent_offsets_;      // per parameter, -1: no slot
  std::vector<const Slot*> param_slots_;  // per parameter, null: no slot
  std::vector<double> plus_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_MARGINALIZATION_SYSTEM_H_
