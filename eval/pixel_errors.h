#ifndef VIO_EVAL_PIXEL_ERRORS_H_
#define VIO_EVAL_PIXEL_ERRORS_H_

// Summary of a set of image-space errors [px], as a frontend's accuracy is
// usually quoted: the median, the 95th percentile, and the share of errors
// beyond 1 px and 3 px (the tail that a robust kernel or an outlier test
// has to catch).

#include <cstddef>
#include <vector>

namespace vio {

struct PixelErrorStats {
  size_t count = 0;
  double median = 0.0;  // [px] mean of the two middle values for even count
  double p95 = 0.0;     // [px] nearest rank: the ceil(0.95 n)-th smallest
  double mean = 0.0;    // [px]
  double max = 0.0;     // [px]
  double share_over_1px = 0.0;  // fraction of errors > 1 px [-]
  double share_over_3px = 0.0;  // fraction of errors > 3 px [-]
};

// The statistics of `errors_px` (all >= 0). With no errors every figure is
// 0 and count is 0.
PixelErrorStats ComputePixelErrorStats(std::vector<double> errors_px);

}  // namespace vio

#endif  // VIO_EVAL_PIXEL_ERRORS_H_
