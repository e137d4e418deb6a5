#include "frontend/frontend_options.h"

#include <cmath>
#include <sstream>

namespace vio {
namespace {

// Writes "<field> must be <expectation> (got <value>)" and returns false.
template <typename T>
bool Fail(const std::string& field, const std::string& expectation, T value,
          std::string* message) {
  std::ostringstream out;
  out << field << " must be " << expectation << " (got " << value << ")";
  *message = out.str();
  return false;
}

bool Positive(double value) { return std::isfinite(value) && value > 0.0; }

}  // namespace

bool KltOptions::Validate(const std::string& prefix,
                          std::string* message) const {
  if (window_px < 3 || window_px % 2 == 0) {
    return Fail(prefix + "window_px", "odd and >= 3", window_px, message);
  }
  if (pyramid_levels < 0 || pyramid_levels > 8) {
    return Fail(prefix + "pyramid_levels", "in [0, 8]", pyramid_levels,
                message);
  }
  if (max_iterations < 1) {
    return Fail(prefix + "max_iterations", ">= 1", max_iterations, message);
  }
  if (!Positive(epsilon_px)) {
    return Fail(prefix + "epsilon_px", "> 0", epsilon_px, message);
  }
  return true;
}

bool FeatureTrackerOptions::Validate(std::string* message) const {
  if (max_features < 1) {
    return Fail("max_features", ">= 1", max_features, message);
  }
  if (!(std::isfinite(min_distance_px) && min_distance_px >= 0.0)) {
    return Fail("min_distance_px", ">= 0", min_distance_px, message);
  }
  if (!(corner_quality > 0.0 && corner_quality < 1.0)) {
    return Fail("corner_quality", "in (0, 1)", corner_quality, message);
  }
  if (border_px < 0) return Fail("border_px", ">= 0", border_px, message);
  if (refill_min_missing < 1 || refill_min_missing > max_features) {
    return Fail("refill_min_missing", "in [1, max_features]",
                refill_min_missing, message);
  }
  if (!klt.Validate("klt_", message)) return false;
  if (!Positive(max_forward_backward_px)) {
    return Fail("max_forward_backward_px", "> 0", max_forward_backward_px,
                message);
  }
  if (!Positive(fundamental_threshold_px)) {
    return Fail("fundamental_threshold_px", "> 0", fundamental_threshold_px,
                message);
  }
  if (!(fundamental_confidence > 0.0 && fundamental_confidence < 1.0)) {
    return Fail("fundamental_confidence", "in (0, 1)", fundamental_confidence,
                message);
  }
  if (fundamental_baseline_frames < 0 || fundamental_baseline_frames > 100) {
    return Fail("fundamental_baseline_frames", "in [0, 100]",
                fundamental_baseline_frames, message);
  }
  if (!Positive(virtual_focal_px)) {
    return Fail("virtual_focal_px", "> 0", virtual_focal_px, message);
  }
  if (!(Positive(anchor_max_correction_px) &&
        anchor_max_correction_px <= 10.0)) {
    return Fail("anchor_max_correction_px", "in (0, 10]",
                anchor_max_correction_px, message);
  }
  if (!(anchor_min_correlation >= -1.0 && anchor_min_correlation < 1.0)) {
    return Fail("anchor_min_correlation", "in [-1, 1)", anchor_min_correlation,
                message);
  }
  if (!Positive(clahe_clip_limit)) {
    return Fail("clahe_clip_limit", "> 0", clahe_clip_limit, message);
  }
  if (clahe_tiles < 1) {
    return Fail("clahe_tiles", ">= 1", clahe_tiles, message);
  }
  return true;
}

bool StereoMatcherOptions::Validate(std::string* message) const {
  if (!klt.Validate("klt_", message)) return false;
  if (!Positive(max_reverse_px)) {
    return Fail("max_reverse_px", "> 0", max_reverse_px, message);
  }
  if (reverse_pyramid_levels < 0 ||
      reverse_pyramid_levels > klt.pyramid_levels) {
    return Fail("reverse_pyramid_levels",
                "in [0, klt_pyramid_levels = " +
                    std::to_string(klt.pyramid_levels) + "]",
                reverse_pyramid_levels, message);
  }
  if (!Positive(max_epipolar_px)) {
    return Fail("max_epipolar_px", "> 0", max_epipolar_px, message);
  }
  return true;
}

bool FrontendOptions::Validate(std::string* message) const {
  if (!tracker.Validate(message)) {
    *message = "tracker." + *message;
    return false;
  }
  if (!stereo_matcher.Validate(message)) {
    *message = "stereo_matcher." + *message;
    return false;
  }
  return true;
}

}  // namespace vio
