#ifndef VIO_ESTIMATOR_VALUE_HISTOGRAM_H_
#define VIO_ESTIMATOR_VALUE_HISTOGRAM_H_

// The distribution of a per-step figure (solver time, residual count) over a
// run of any length, in memory that does not grow with the number of steps:
// counts in bins instead of a list of every value. It answers the
// nearest-rank quantiles a summary prints (median, p95, max) and the count.
//
// Bins, with values measured in units of `unit` (u = value / unit):
//   - below 2^exact_bits units, one bin per multiple of the unit, centred on
//     it: bin k holds [k - 0.5, k + 0.5) units and stands for k units;
//   - above, 2^exact_bits bins per octave [2^e, 2^(e+1)), each 2^(e -
//     exact_bits) units wide and standing for its centre: a relative
//     precision of 2^-(exact_bits + 1) (half a bin).
// So with `unit` equal to the printed resolution, a quantile below
// 2^exact_bits units prints as the exact one does (the bin rounds as printf
// rounds, except for a value lying on a half-unit boundary to within the
// double's precision); above it differs by at most half a bin. The bins are
// allocated up to the highest one hit: memory grows with the log of the
// largest value, never with the number of values.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vio {

class ValueHistogram {
 public:
  // unit > 0 and 1 <= exact_bits <= 24 (std::invalid_argument otherwise).
  ValueHistogram(double unit, int exact_bits);

  // Counts one value. Negative values count as 0; a NaN is not counted.
  void Add(double value);

  int64_t count() const { return count_; }
  bool empty() const { return count_ == 0; }

  // The nearest-rank q-quantile (0 <= q <= 1), as a sorted list's element
  // k = round(q * (count - 1)) (q = 1: the largest), as its bin stands for
  // it; 0 when empty.
  double Quantile(double q) const;

 private:
  size_t BinOf(double u) const;
  double ValueOf(size_t bin) const;

  double unit_;
  int exact_bits_;
  std::vector<uint32_t> counts_;  // by bin, up to the highest one hit
  int64_t count_ = 0;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_VALUE_HISTOGRAM_H_
