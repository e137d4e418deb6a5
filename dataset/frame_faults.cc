#include "dataset/frame_faults.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace vio {
namespace {

// splitmix64's finaliser: a well-mixed 64-bit value of its input, the same
// on every platform (std::uniform_*_distribution is not).
uint64_t Mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A number in [0, 1) drawn from the seed and up to two keys.
double Uniform(uint32_t seed, int64_t a, int64_t b = 0, uint64_t salt = 0) {
  const uint64_t h =
      Mix(Mix(Mix(seed ^ (salt << 32)) ^ static_cast<uint64_t>(a)) ^
          static_cast<uint64_t>(b));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

int64_t Nanoseconds(double s) { return std::llround(s * 1e9); }

}  // namespace

std::string FrameFault::Describe() const {
  char buffer[160];
  switch (kind) {
    case FrameFaultKind::kBlackout:
      std::snprintf(buffer, sizeof(buffer),
                    "a %.3f s camera blackout at %.3f s", duration_s, t_s);
      break;
    case FrameFaultKind::kEmptyFrames:
      std::snprintf(buffer, sizeof(buffer),
                    "%.0f %% of the frames without features over %.3f s at "
                    "%.3f s",
                    100 * fraction, duration_s, t_s);
      break;
    case FrameFaultKind::kHalfRate:
      std::snprintf(buffer, sizeof(buffer), "frame rate halved at %.3f s", t_s);
      break;
    case FrameFaultKind::kOutliers:
      std::snprintf(buffer, sizeof(buffer),
                    "%.0f %% outlier observations over %.3f s at %.3f s",
                    100 * fraction, duration_s, t_s);
      break;
    case FrameFaultKind::kTimeOffset:
      std::snprintf(buffer, sizeof(buffer),
                    "camera stamps moved by %.4f s (unconfigured offset)",
                    offset_s);
      break;
  }
  return buffer;
}

bool FrameFault::Validate(std::string* message) const {
  const auto fail = [&](const std::string& text) {
    if (message != nullptr) *message = text;
    return false;
  };
  if (!std::isfinite(t_s) || t_s < 0) return fail("t_s must be >= 0");
  if (!std::isfinite(duration_s) || duration_s < 0) {
    return fail("duration_s must be >= 0");
  }
  const bool spans = kind == FrameFaultKind::kBlackout ||
                     kind == FrameFaultKind::kEmptyFrames ||
                     kind == FrameFaultKind::kOutliers;
  if (spans && duration_s <= 0) return fail("duration_s must be > 0");
  const bool shares =
      kind == FrameFaultKind::kEmptyFrames || kind == FrameFaultKind::kOutliers;
  if (shares && !(fraction > 0 && fraction <= 1)) {
    return fail("fraction must be in (0, 1]");
  }
  if (kind == FrameFaultKind::kOutliers && (width < 1 || height < 1)) {
    return fail("width and height must be >= 1 px");
  }
  if (kind == FrameFaultKind::kTimeOffset &&
      !(std::isfinite(offset_s) && std::fabs(offset_s) < 1.0)) {
    return fail("offset_s must be finite and under 1 s");
  }
  return true;
}

std::vector<FeatureFrame> WithFrameFault(std::vector<FeatureFrame> frames,
                                         const FrameFault& fault,
                                         int64_t start_ns) {
  std::string message;
  if (!fault.Validate(&message)) {
    throw std::invalid_argument("frame fault: " + message);
  }
  if (fault.kind == FrameFaultKind::kTimeOffset) {
    for (FeatureFrame& f : frames) f.t_ns += Nanoseconds(fault.offset_s);
    return frames;
  }
  const int64_t begin = start_ns + Nanoseconds(fault.t_s);
  const int64_t end =
      fault.duration_s > 0 ? begin + Nanoseconds(fault.duration_s) : INT64_MAX;
  std::vector<FeatureFrame> out;
  int in_span = 0;
  int64_t half_rate_index = 0;  // frames since t_s (kHalfRate)
  for (FeatureFrame& f : frames) {
    if (f.t_ns < begin || f.t_ns >= end) {
      out.push_back(std::move(f));
      continue;
    }
    ++in_span;
    switch (fault.kind) {
      case FrameFaultKind::kBlackout:
        continue;
      case FrameFaultKind::kHalfRate:
        if (half_rate_index++ % 2 == 1) continue;
        break;
      case FrameFaultKind::kEmptyFrames:
        if (Uniform(fault.seed, f.t_ns) < fault.fraction) continue;
        break;
      case FrameFaultKind::kOutliers:
        for (FeatureObservation& o : f.observations) {
          if (Uniform(fault.seed, f.t_ns, o.feature_id, 1 + o.camera) >=
              fault.fraction) {
            continue;
          }
          const double u =
              Uniform(fault.seed, f.t_ns, o.feature_id, 10 + o.camera);
          const double v =
              Uniform(fault.seed, f.t_ns, o.feature_id, 20 + o.camera);
          o.uv = Eigen::Vector2d(u * (fault.width - 1), v * (fault.height - 1));
        }
        break;
      case FrameFaultKind::kTimeOffset:
        break;
    }
    out.push_back(std::move(f));
  }
  if (in_span == 0) {
    throw std::invalid_argument("frame fault: " + fault.Describe() +
                                ": no frame in its span");
  }
  return out;
}

}  // namespace vio
