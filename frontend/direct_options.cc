#include "frontend/direct_options.h"

#include <cmath>
#include <sstream>

namespace vio {
namespace {

template <typename T>
bool Fail(const std::string& field, const std::string& expectation, T value,
          std::string* message) {
  std::ostringstream out;
  out << field << " must be " << expectation << " (got " << value << ")";
  *message = out.str();
  return false;
}

bool Positive(double value) { return std::isfinite(value) && value > 0.0; }
bool NonNegative(double value) { return std::isfinite(value) && value >= 0.0; }

}  // namespace

bool StereoDepthOptions::Validate(std::string* message) const {
  if (level < 0 || level > 6) return Fail("level", "in [0, 6]", level, message);
  if (!NonNegative(min_gradient)) {
    return Fail("min_gradient", ">= 0", min_gradient, message);
  }
  if (!(min_line_cosine >= 0.0 && min_line_cosine < 1.0)) {
    return Fail("min_line_cosine", "in [0, 1)", min_line_cosine, message);
  }
  if (!Positive(min_depth_m)) {
    return Fail("min_depth_m", "> 0", min_depth_m, message);
  }
  if (!(std::isfinite(max_depth_m) && max_depth_m > min_depth_m)) {
    return Fail("max_depth_m", "> min_depth_m", max_depth_m, message);
  }
  if (!(min_ncc > -1.0 && min_ncc < 1.0)) {
    return Fail("min_ncc", "in (-1, 1)", min_ncc, message);
  }
  if (!(std::isfinite(uniqueness_ratio) && uniqueness_ratio >= 1.0)) {
    return Fail("uniqueness_ratio", ">= 1", uniqueness_ratio, message);
  }
  if (!Positive(sigma_intensity)) {
    return Fail("sigma_intensity", "> 0", sigma_intensity, message);
  }
  if (!NonNegative(sigma_epipolar_px)) {
    return Fail("sigma_epipolar_px", ">= 0", sigma_epipolar_px, message);
  }
  return true;
}

const char* DirectSolverName(DirectSolver solver) {
  return solver == DirectSolver::kCeres ? "ceres" : "notes";
}

bool ParseDirectSolver(const std::string& text, DirectSolver* solver) {
  if (text == "notes") {
    *solver = DirectSolver::kNotesLm;
  } else if (text == "ceres") {
    *solver = DirectSolver::kCeres;
  } else {
    return false;
  }
  return true;
}

bool DirectTrackerOptions::Validate(std::string* message) const {
  if (finest_level < 0) {
    return Fail("finest_level", ">= 0", finest_level, message);
  }
  if (coarsest_level < finest_level) {
    return Fail("coarsest_level", ">= finest_level", coarsest_level, message);
  }
  if (max_iterations < 1) {
    return Fail("max_iterations", ">= 1", max_iterations, message);
  }
  if (!Positive(min_step)) return Fail("min_step", "> 0", min_step, message);
  if (!Positive(lambda_floor)) {
    return Fail("lambda_floor", "> 0", lambda_floor, message);
  }
  if (!(std::isfinite(max_lambda) && max_lambda > lambda_floor)) {
    return Fail("max_lambda", "> lambda_floor", max_lambda, message);
  }
  if (!Positive(sigma_intensity)) {
    return Fail("sigma_intensity", "> 0", sigma_intensity, message);
  }
  if (!NonNegative(huber_scale)) {
    return Fail("huber_scale", ">= 0", huber_scale, message);
  }
  if (!NonNegative(stereo_weight)) {
    return Fail("stereo_weight", ">= 0", stereo_weight, message);
  }
  if (min_residuals < 10) {
    return Fail("min_residuals", ">= 10", min_residuals, message);
  }
  if (max_points != 0 && max_points < min_residuals) {
    return Fail("max_points", "0 or >= min_residuals", max_points, message);
  }
  return true;
}

bool DirectOdometryOptions::Validate(std::string* message) const {
  if (pyramid_levels < 1 || pyramid_levels > 8) {
    return Fail("pyramid_levels", "in [1, 8]", pyramid_levels, message);
  }
  std::string nested;
  if (!depth.Validate(&nested)) {
    *message = "depth." + nested;
    return false;
  }
  if (!tracker.Validate(&nested)) {
    *message = "tracker." + nested;
    return false;
  }
  if (tracker.coarsest_level >= pyramid_levels) {
    return Fail("tracker.coarsest_level", "< pyramid_levels",
                tracker.coarsest_level, message);
  }
  if (depth.level >= pyramid_levels) {
    return Fail("depth.level", "< pyramid_levels", depth.level, message);
  }
  if (tracker.finest_level < depth.level) {
    return Fail("tracker.finest_level", ">= depth.level", tracker.finest_level,
                message);
  }
  if (!(min_overlap >= 0.0 && min_overlap <= 1.0)) {
    return Fail("min_overlap", "in [0, 1]", min_overlap, message);
  }
  if (!Positive(max_distance_over_depth)) {
    return Fail("max_distance_over_depth", "> 0", max_distance_over_depth,
                message);
  }
  if (min_keyframe_points < 10) {
    return Fail("min_keyframe_points", ">= 10", min_keyframe_points, message);
  }
  return true;
}

}  // namespace vio
