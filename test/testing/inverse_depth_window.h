#ifndef VIO_TEST_TESTING_INVERSE_DEPTH_WINDOW_H_
#define VIO_TEST_TESTING_INVERSE_DEPTH_WINDOW_H_

// A small sliding window built from the project's own visual factors, for the
// window solver and the marginalisation tests: 5 body poses (PoseManifold) on
// a curved path looking at a wall, a constant camera extrinsic, 40 landmarks
// held as inverse depths in their anchor camera (pose 0 or 1), each seen by
// every later pose through a ReprojectionFactor (1 px noise, Huber loss; one
// in five with Ceres' TolerantLoss, whose rho'' > 0 exercises the Triggs
// correction), and a MarginalizationPrior on poses 0 and 1 (random SPD
// information, away from the current values) that fixes the gauge and the
// scale. States start perturbed from the truth (poses by centimetres and
// half a degree, depths by 10 %). Deterministic (fixed seed).
//
// It also linearises any subset of it with Ceres itself (its evaluator, the
// losses applied by Ceres' own corrector), as the independent reference.

#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "factors/marginalization_prior.h"
#include "factors/pose_manifold.h"

namespace vio {
namespace testing {

class InverseDepthWindow {
 public:
  static constexpr int kPoses = 5;
  static constexpr int kLandmarks = 40;

  struct Residual {
    std::shared_ptr<ceres::CostFunction> cost;
    const ceres::LossFunction* loss = nullptr;
    std::vector<double*> blocks;
    int anchor = -1;  // visual residuals: the anchor pose's index
  };

  // tolerant_loss: one landmark in five on TolerantLoss (else all Huber).
  explicit InverseDepthWindow(bool tolerant_loss = true, unsigned seed = 7);

  double* Pose(int i) { return poses_[i].data(); }
  double* Rho(int k) { return &rho_[k]; }
  double* Extrinsic() { return extrinsic_.data(); }
  int AnchorOf(int k) const { return anchor_[k]; }
  const std::vector<Residual>& residuals() const { return residuals_; }
  const MarginalizationPrior& prior() const { return *prior_; }
  const PoseManifold* pose_manifold() const { return &pose_manifold_; }
  const ceres::LossFunction* huber() const { return huber_.get(); }

  // A ceres::Problem over the given residuals (not owning anything), poses on
  // PoseManifold, the extrinsic constant.
  std::unique_ptr<ceres::Problem> CeresProblem(
      const std::vector<const Residual*>& residuals);
  // H = J^T J and g = J^T r over the tangent space of `order` (every block
  // the residuals touch must be listed), linearised by Ceres.
  void CeresLinearise(const std::vector<const Residual*>& residuals,
                      const std::vector<double*>& order, Eigen::MatrixXd* H,
                      Eigen::VectorXd* g);
  std::vector<const Residual*> All() const;

  bool IsPose(const double* x) const;
  int TangentSize(const double* x) const { return IsPose(x) ? 6 : 1; }

 private:
  std::array<std::array<double, 7>, kPoses> poses_{};
  std::array<double, kLandmarks> rho_{};
  std::array<int, kLandmarks> anchor_{};
  std::array<double, 7> extrinsic_{};
  std::vector<Residual> residuals_;
  std::unique_ptr<MarginalizationPrior> prior_;
  std::unique_ptr<ceres::LossFunction> huber_;
  std::unique_ptr<ceres::LossFunction> tolerant_;
  PoseManifold pose_manifold_;
};

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_INVERSE_DEPTH_WINDOW_H_
