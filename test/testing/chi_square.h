#ifndef VIO_TEST_TESTING_CHI_SQUARE_H_
#define VIO_TEST_TESTING_CHI_SQUARE_H_

// Chi-square quantiles for consistency tests (NEES, NIS), by the
// Wilson-Hilferty cube-root approximation: X/nu ~ N(1 - 2/(9 nu), 2/(9 nu))
// cubed. Its relative error is below 1e-3 for nu >= 20 (checked against
// published table values in kalman_filter_test).

#include <cmath>

namespace vio {
namespace testing {

// The standard normal quantile for the two 95 % band edges.
constexpr double kZ975 = 1.959963984540054;

// The p-quantile of chi-square with nu degrees of freedom, for p = 0.025
// (z = -kZ975) or 0.975 (z = +kZ975).
inline double ChiSquareQuantile(double nu, double z) {
  const double a = 2.0 / (9.0 * nu);
  const double c = 1.0 - a + z * std::sqrt(a);
  return nu * c * c * c;
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_CHI_SQUARE_H_
