#include "estimator/init_attempt.h"

#include <cstdio>
#include <map>
#include <utility>

namespace vio {

const char* InitFailureName(InitFailure failure) {
  switch (failure) {
    case InitFailure::kNone:
      return "none";
    case InitFailure::kTooFewFrames:
      return "frames span too little time";
    case InitFailure::kImuUnavailable:
      return "IMU does not cover the frames";
    case InitFailure::kNotStill:
      return "IMU not still";
    case InitFailure::kImageMoving:
      return "features moving";
    case InitFailure::kNoImageVerdict:
      return "too few features tracked to judge stillness";
    case InitFailure::kLowImuExcitation:
      return "too little IMU excitation";
    case InitFailure::kFewCorrespondences:
      return "too few correspondences";
    case InitFailure::kLowParallax:
      return "too little parallax";
    case InitFailure::kFewInliers:
      return "too few essential-matrix inliers";
    case InitFailure::kRotationMismatch:
      return "visual rotations disagree with the gyroscope";
    case InitFailure::kPnpFailed:
      return "PnP failed";
    case InitFailure::kReprojectionError:
      return "bundle adjustment reprojection error too large";
    case InitFailure::kTooManyOutliers:
      return "too many outlier sightings";
    case InitFailure::kFewPointsLeft:
      return "too few points left after the outliers' removal";
    case InitFailure::kFewStereoPoints:
      return "too few stereo points";
    case InitFailure::kNegativeScale:
      return "negative scale";
    case InitFailure::kScaleUncertain:
      return "scale not observable";
    case InitFailure::kGravityMagnitude:
      return "gravity magnitude far from the configured one";
    case InitFailure::kImplausibleSpeed:
      return "implausible speed";
    case InitFailure::kRefinementScaleChange:
      return "joint adjustment changed the scale";
    case InitFailure::kRefinementFailed:
      return "joint adjustment failed";
  }
  return "?";
}

std::string DescribeInitAttempt(const InitAttempt& a) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "%s: %s (%.4g vs limit %.4g)",
                InitMethodName(a.method), InitFailureName(a.reason), a.value,
                a.limit);
  return buffer;
}

std::string DescribeInitFailures(const std::vector<InitAttempt>& attempts) {
  if (attempts.empty()) return "no attempt was made";
  // Per method (in the order first tried): the last attempt, the count per
  // reason and the total.
  std::vector<InitMethod> order;
  std::map<InitMethod, const InitAttempt*> last;
  std::map<InitMethod, std::map<InitFailure, int>> counts;
  std::map<InitMethod, int> totals;
  for (const InitAttempt& a : attempts) {
    if (last.count(a.method) == 0) order.push_back(a.method);
    last[a.method] = &a;
    ++counts[a.method][a.reason];
    ++totals[a.method];
  }
  std::string out;
  for (InitMethod m : order) {
    if (!out.empty()) out += "; ";
    out += "last " + DescribeInitAttempt(*last[m]) + ", " +
           std::to_string(totals[m]) + " attempts (";
    bool first = true;
    for (const auto& [reason, n] : counts[m]) {
      if (!first) out += ", ";
      first = false;
      out += std::string(InitFailureName(reason)) + " " + std::to_string(n);
    }
    out += ")";
  }
  return out;
}

}  // namespace vio
