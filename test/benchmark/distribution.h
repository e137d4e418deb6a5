#ifndef VIO_TEST_BENCHMARK_DISTRIBUTION_H_
#define VIO_TEST_BENCHMARK_DISTRIBUTION_H_

// init_benchmark's figures over trials: median, p90 and max of a sample.

#include <cstdio>
#include <string>
#include <vector>

#include "test/benchmark/init_diagnosis.h"

namespace vio {

struct Distribution {
  std::vector<double> values;
  void Add(double v) { values.push_back(v); }
  double Quantile(double q) const { return diagnosis::Quantile(values, q); }
  std::string Describe(double scale, const char* unit) const {
    char b[160];
    std::snprintf(b, sizeof(b), "median %.3g, p90 %.3g, max %.3g %s",
                  scale * Quantile(0.5), scale * Quantile(0.9),
                  scale * Quantile(1.0), unit);
    return b;
  }
};

}  // namespace vio

#endif  // VIO_TEST_BENCHMARK_DISTRIBUTION_H_
