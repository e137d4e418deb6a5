#ifndef VIO_TEST_TESTING_JACOBIAN_TEST_UTILS_H_
#define VIO_TEST_TESTING_JACOBIAN_TEST_UTILS_H_

// ExpectJacobianNear: an analytic Jacobian against central differences of the
// function it claims to differentiate (in the shape of Basalt's
// test_utils.h test_jacobian). f maps a tangent increment x (around x0) to a
// tangent-space output; the caller applies its own perturbation convention
// inside f, so the check is on the tangent space.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <string>

namespace vio {
namespace testing {

// Passes when max |J - J_numeric| <= tolerance * max(max |J_numeric|, 1e-9),
// i.e. relative to the largest entry of the block.
template <typename Function>
void ExpectJacobianNear(const std::string& name, const Eigen::MatrixXd& J,
                        Function f, const Eigen::VectorXd& x0,
                        double tolerance = 1e-6, double step = 1e-6) {
  const Eigen::VectorXd y0 = f(x0);
  ASSERT_EQ(J.rows(), y0.size()) << name;
  ASSERT_EQ(J.cols(), x0.size()) << name;
  Eigen::MatrixXd numeric(J.rows(), J.cols());
  for (int k = 0; k < x0.size(); ++k) {
    Eigen::VectorXd x_plus = x0, x_minus = x0;
    x_plus[k] += step;
    x_minus[k] -= step;
    numeric.col(k) = (f(x_plus) - f(x_minus)) / (2.0 * step);
  }
  const double scale = std::max(numeric.cwiseAbs().maxCoeff(), 1e-9);
  const double error = (J - numeric).cwiseAbs().maxCoeff();
  EXPECT_LE(error, tolerance * scale)
      << name << ": analytic\n"
      << J << "\nnumeric\n"
      << numeric << "\nrelative error " << error / scale;
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_JACOBIAN_TEST_UTILS_H_
