#include "config/frontend_config.h"

namespace vio {
namespace {

KltOptions ReadKlt(const YamlNode& node) {
  KltOptions klt;
  klt.window_px = node.Get<int>("klt_window_px");
  klt.pyramid_levels = node.Get<int>("klt_pyramid_levels");
  klt.max_iterations = node.Get<int>("klt_max_iterations");
  klt.epsilon_px = node.Get<double>("klt_epsilon_px");
  return klt;
}

FeatureTrackerOptions ReadTracker(const YamlNode& node) {
  FeatureTrackerOptions o;
  o.max_features = node.Get<int>("max_features");
  o.min_distance_px = node.Get<double>("min_distance_px");
  o.corner_quality = node.Get<double>("corner_quality");
  o.border_px = node.Get<int>("border_px");
  o.refill_min_missing = node.Get<int>("refill_min_missing");
  o.klt = ReadKlt(node);
  o.max_forward_backward_px = node.Get<double>("max_forward_backward_px");
  o.fundamental_check = node.Get<bool>("fundamental_check");
  o.fundamental_threshold_px = node.Get<double>("fundamental_threshold_px");
  o.fundamental_confidence = node.Get<double>("fundamental_confidence");
  o.fundamental_baseline_frames = node.Get<int>("fundamental_baseline_frames");
  o.virtual_focal_px = node.Get<double>("virtual_focal_px");
  o.anchor_refinement = node.Get<bool>("anchor_refinement");
  o.anchor_max_correction_px = node.Get<double>("anchor_max_correction_px");
  o.anchor_min_correlation = node.Get<double>("anchor_min_correlation");
  o.clahe = node.Get<bool>("clahe");
  o.clahe_clip_limit = node.Get<double>("clahe_clip_limit");
  o.clahe_tiles = node.Get<int>("clahe_tiles");
  ValidateAt(node, o);
  return o;
}

StereoMatcherOptions ReadStereoMatcher(const YamlNode& node) {
  StereoMatcherOptions o;
  o.klt = ReadKlt(node);
  o.equalize = node.Get<bool>("equalize");
  o.max_reverse_px = node.Get<double>("max_reverse_px");
  o.reverse_pyramid_levels = node.Get<int>("reverse_pyramid_levels");
  o.max_epipolar_px = node.Get<double>("max_epipolar_px");
  o.start_from_previous = node.Get<bool>("start_from_previous");
  ValidateAt(node, o);
  return o;
}

}  // namespace

FrontendOptions ReadFrontendOptions(const YamlNode& frontend) {
  FrontendOptions options;
  options.stereo = frontend.Get<bool>("stereo");
  options.tracker = ReadTracker(frontend.Child("tracker"));
  options.stereo_matcher = ReadStereoMatcher(frontend.Child("stereo_matcher"));
  ValidateAt(frontend, options);
  return options;
}

FrontendOptions LoadFrontendOptions(const std::string& path) {
  return ReadFrontendOptions(YamlNode::LoadFile(path).Child("frontend"));
}

}  // namespace vio
