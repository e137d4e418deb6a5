#include "estimator/value_histogram.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

// Octaves above the exact bins; larger values count in the top bin (with a
// 10 us unit and 11 exact bits that is beyond 2^51 s).
constexpr int kMaxOctaves = 40;

}  // namespace

ValueHistogram::ValueHistogram(double unit, int exact_bits)
    : unit_(unit), exact_bits_(exact_bits) {
  if (!(unit > 0.0) || !std::isfinite(unit) || exact_bits < 1 ||
      exact_bits > 24) {
    throw std::invalid_argument(
        "ValueHistogram: unit must be > 0 and exact_bits in 1..24 (got " +
        std::to_string(unit) + ", " + std::to_string(exact_bits) + ")");
  }
}

// Bins 0..2^m: the exact ones (bin 2^m holds [2^m - 0.5, 2^m) units); then
// 2^m per octave e >= m, bin s of the octave holding
// [2^e (1 + s 2^-m), 2^e (1 + (s + 1) 2^-m)).
size_t ValueHistogram::BinOf(double u) const {
  const int64_t per_octave = int64_t{1} << exact_bits_;
  if (u < static_cast<double>(per_octave)) {
    return static_cast<size_t>(std::llround(u));
  }
  int e = std::ilogb(u);
  int64_t s = 0;
  if (e - exact_bits_ >= kMaxOctaves) {
    e = exact_bits_ + kMaxOctaves - 1;
    s = per_octave - 1;
  } else {
    const double fraction = std::ldexp(u, -e) - 1.0;  // [0, 1)
    s = std::clamp<int64_t>(
        static_cast<int64_t>(std::floor(std::ldexp(fraction, exact_bits_))), 0,
        per_octave - 1);
  }
  return static_cast<size_t>(per_octave + 1 + (e - exact_bits_) * per_octave +
                             s);
}

double ValueHistogram::ValueOf(size_t bin) const {
  const size_t per_octave = size_t{1} << exact_bits_;
  if (bin <= per_octave) return static_cast<double>(bin) * unit_;
  const size_t j = bin - per_octave - 1;
  const int e = exact_bits_ + static_cast<int>(j / per_octave);
  const double s = static_cast<double>(j % per_octave);
  return std::ldexp(1.0 + std::ldexp(s + 0.5, -exact_bits_), e) * unit_;
}

void ValueHistogram::Add(double value) {
  if (std::isnan(value)) return;
  const double u = std::max(0.0, value / unit_);
  const size_t bin = BinOf(u);
  if (bin >= counts_.size()) counts_.resize(bin + 1, 0);
  ++counts_[bin];
  ++count_;
}

double ValueHistogram::Quantile(double q) const {
  if (count_ == 0) return 0.0;
  const double clamped = std::clamp(q, 0.0, 1.0);
  const int64_t k = std::min<int64_t>(
      static_cast<int64_t>(clamped * static_cast<double>(count_ - 1) + 0.5),
      count_ - 1);
  int64_t below = 0;  // values in the bins before `bin`
  for (size_t bin = 0; bin < counts_.size(); ++bin) {
    below += counts_[bin];
    if (below > k) return ValueOf(bin);
  }
  return ValueOf(counts_.size() - 1);
}

}  // namespace vio
