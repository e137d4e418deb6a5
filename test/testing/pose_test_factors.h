#ifndef VIO_TEST_TESTING_POSE_TEST_FACTORS_H_
#define VIO_TEST_TESTING_POSE_TEST_FACTORS_H_

// Small analytic factors on pose (7, PoseManifold) and Euclidean blocks, for
// testing the marginalisation without the IMU and visual factors. Residuals
// are whitened by a square-root information W; Jacobians follow the project's
// right perturbation and are lifted to the ambient space like every factor.
// Their Jacobians are checked numerically in marginalization_test.cc.

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vio {
namespace testing {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// r = W [R_i^T (t_j - t_i) - t_ij;  Log(q_ij^-1 q_i^-1 q_j)]
// blocks: pose_i (7), pose_j (7).
class RelativePoseTestFactor final : public ceres::SizedCostFunction<6, 7, 7> {
 public:
  RelativePoseTestFactor(const Eigen::Vector3d& t_ij,
                         const Eigen::Quaterniond& q_ij, const Matrix6d& W)
      : t_ij_(t_ij), q_ij_(q_ij), W_(W) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d t_ij_;  // [m]
  Eigen::Quaterniond q_ij_;
  Matrix6d W_;
};

// r = W [t - t_m;  Log(q_m^-1 q)];  blocks: pose (7).
class PosePriorTestFactor final : public ceres::SizedCostFunction<6, 7> {
 public:
  PosePriorTestFactor(const Eigen::Vector3d& t_m, const Eigen::Quaterniond& q_m,
                      const Matrix6d& W)
      : t_m_(t_m), q_m_(q_m), W_(W) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d t_m_;  // [m]
  Eigen::Quaterniond q_m_;
  Matrix6d W_;
};

// A point l (3, Euclidean) seen from a pose: r = W (R^T (l - t) - z), with W
// k x 3 (k = 1 gives a rank-one observation); blocks: pose (7), point (3).
class PointTestFactor final : public ceres::CostFunction {
 public:
  PointTestFactor(const Eigen::Vector3d& z,
                  const Eigen::Matrix<double, Eigen::Dynamic, 3>& W);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d z_;  // [m], in the body frame
  Eigen::Matrix<double, Eigen::Dynamic, 3> W_;
};

// r = W (b_j - b_i - d) on two Euclidean blocks of size 3.
class DifferenceTestFactor final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  DifferenceTestFactor(const Eigen::Vector3d& d, const Eigen::Matrix3d& W)
      : d_(d), W_(W) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d d_;
  Eigen::Matrix3d W_;
};

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_POSE_TEST_FACTORS_H_
