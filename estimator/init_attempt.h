#ifndef VIO_ESTIMATOR_INIT_ATTEMPT_H_
#define VIO_ESTIMATOR_INIT_ATTEMPT_H_

// Why an attempt to start the estimator failed, as data: every initialiser
// returns one of these reasons with the value it measured and the limit it
// broke, the estimator logs them in its summary (EstimatorSummary::
// init_attempts), and a tool prints them. Nothing here prints.

#include <cstdint>
#include <string>
#include <vector>

#include "estimator/initialization_options.h"

namespace vio {

enum class InitFailure {
  kNone,
  kTooFewFrames,           // the frames do not span enough time yet [s]
  kImuUnavailable,         // the IMU does not cover the frames (a gap)
  kNotStill,               // static: the IMU block means vary [m/s^2 or rad/s]
  kImageMoving,            // static: the features move [px]
  kNoImageVerdict,         // static: too few features tracked over the span
  kLowImuExcitation,       // mono: std of the mean specific force [m/s^2]
  kFewCorrespondences,     // mono: features shared by the reference pair
  kLowParallax,            // mono: rotation-compensated median parallax [px]
  kFewInliers,             // mono: essential-matrix inliers in front
  kRotationMismatch,       // mono: essential vs gyroscope rotation [deg]
  kPnpFailed,              // a frame could not be placed: PnP inliers
  kReprojectionError,      // mono: RMS after the bundle adjustment [px]
  kTooManyOutliers,        // mono: share of the sightings removed [-]
  kFewPointsLeft,          // mono: points left after the outliers' removal
  kFewStereoPoints,        // stereo: points triangulated from the pair
  kNegativeScale,          // mono: least-squares scale <= 0
  kScaleUncertain,         // mono: relative std of the scale
  kGravityMagnitude,       // | |g| - g | of the free alignment [m/s^2]
  kImplausibleSpeed,       // an aligned velocity [m/s]
  kRefinementScaleChange,  // the joint adjustment moved the scale [-]
  kRefinementFailed,       // the joint adjustment broke a failure rule
};

// A short English name: "too little parallax", "IMU not still", ...
const char* InitFailureName(InitFailure failure);

// One failed attempt.
struct InitAttempt {
  int64_t t_ns = 0;  // camera stamp of the frame it was tried at [ns]
  InitMethod method = InitMethod::kAuto;
  InitFailure reason = InitFailure::kNone;
  double value = 0.0;  // what was measured (unit per reason, above)
  double limit = 0.0;  // the limit it broke
};

// A refused attempt at the frame stamped t_ns: what every initialiser
// returns when one of its checks fails.
inline InitAttempt RefusedAttempt(int64_t t_ns, InitMethod method,
                                  InitFailure reason, double value,
                                  double limit) {
  InitAttempt a;
  a.t_ns = t_ns;
  a.method = method;
  a.reason = reason;
  a.value = value;
  a.limit = limit;
  return a;
}

// "mono: too little parallax (12.3 < 25)".
std::string DescribeInitAttempt(const InitAttempt& attempt);

// Why no start was accepted: per method tried, its last failure and how
// often each reason occurred, e.g.
//   "last mono: too little IMU excitation (0.02 vs limit 0.25), 560 attempts
//   (too little IMU excitation 540, too little parallax 20)"
// "no attempt was made" when the log is empty.
std::string DescribeInitFailures(const std::vector<InitAttempt>& attempts);

}  // namespace vio

#endif  // VIO_ESTIMATOR_INIT_ATTEMPT_H_
