#include "estimator/value_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace vio {
namespace {

// The nearest-rank quantile of the whole list, as vio_replay computed it
// before the histograms: element round(q (n - 1)) of the sorted values.
double ExactQuantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const size_t k = static_cast<size_t>(q * (values.size() - 1) + 0.5);
  return values[std::min(k, values.size() - 1)];
}

std::string Ms(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", 1e3 * seconds);
  return text;
}

// Solver-like step times: log-normal around 2 ms, with a tail past the
// exact bins (20.48 ms), as vio_replay's summary prints them (0.01 ms).
TEST(ValueHistogram, TimeQuantilesPrintAsTheExactOnes) {
  std::mt19937 rng(42);
  std::lognormal_distribution<double> step(std::log(2e-3), 0.6);
  for (int n : {1, 2, 7, 100, 1001, 5000}) {
    ValueHistogram h(1e-5, 11);
    std::vector<double> values;
    for (int i = 0; i < n; ++i) {
      const double t = step(rng);
      values.push_back(t);
      h.Add(t);
    }
    ASSERT_EQ(h.count(), n);
    for (double q : {0.0, 0.5, 0.95, 1.0}) {
      const double exact = ExactQuantile(values, q);
      if (exact < 20.48e-3) {
        EXPECT_EQ(Ms(h.Quantile(q)), Ms(exact)) << "n " << n << " q " << q;
      } else {  // half a bin of 1/2048 of the value
        EXPECT_NEAR(h.Quantile(q), exact, exact / 4096.0)
            << "n " << n << " q " << q;
      }
    }
  }
}

TEST(ValueHistogram, LargeValuesWithinHalfABin) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> big(0.03, 40.0);  // [s]
  ValueHistogram h(1e-5, 11);
  std::vector<double> values;
  for (int i = 0; i < 999; ++i) {
    values.push_back(big(rng));
    h.Add(values.back());
  }
  for (int i = 0; i <= 20; ++i) {
    const double q = 0.05 * i;
    const double exact = ExactQuantile(values, q);
    // Half a bin: 2^(e - 12) units in the octave [2^e, 2^(e+1)) units.
    const double half_bin =
        std::ldexp(1.0, std::ilogb(exact / 1e-5) - 12) * 1e-5;
    EXPECT_NEAR(h.Quantile(q), exact, half_bin) << "q " << q;
  }
}

TEST(ValueHistogram, CountsAreExactBelowTheExactBits) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> residuals(0, 8191);
  ValueHistogram h(1.0, 13);
  std::vector<double> values;
  for (int i = 0; i < 2000; ++i) {
    values.push_back(residuals(rng));
    h.Add(values.back());
  }
  for (double q : {0.0, 0.25, 0.5, 0.95, 1.0}) {
    EXPECT_EQ(h.Quantile(q), ExactQuantile(values, q)) << "q " << q;
  }
}

TEST(ValueHistogram, EmptyNegativeAndNaN) {
  ValueHistogram h(1e-5, 11);
  EXPECT_TRUE(h.empty());
  EXPECT_EQ(h.Quantile(0.5), 0.0);
  h.Add(std::nan(""));
  EXPECT_TRUE(h.empty());
  h.Add(-1.0);
  EXPECT_EQ(h.count(), 1);
  EXPECT_EQ(h.Quantile(1.0), 0.0);
  h.Add(1e300);  // beyond the last octave: the top bin, still counted
  EXPECT_EQ(h.count(), 2);
  EXPECT_GT(h.Quantile(1.0), 1e6);
}

TEST(ValueHistogram, RefusesBadBins) {
  EXPECT_THROW(ValueHistogram(0.0, 11), std::invalid_argument);
  EXPECT_THROW(ValueHistogram(1e-5, 0), std::invalid_argument);
  EXPECT_THROW(ValueHistogram(1e-5, 25), std::invalid_argument);
}

}  // namespace
}  // namespace vio
