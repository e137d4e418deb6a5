#include "frontend/image_frontend.h"

#include <stdexcept>
#include <string>

namespace vio {
namespace {

const FrontendOptions& Validated(const FrontendOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("FrontendOptions: " + message);
  }
  return options;
}

}  // namespace

ImageFrontend::ImageFrontend(const CameraModel& cam0, const CameraModel* cam1,
                             const FrontendOptions& options)
    : tracker_(cam0, Validated(options).tracker, 0) {
  if (options.stereo) {
    if (cam1 == nullptr) {
      throw std::invalid_argument(
          "ImageFrontend: stereo needs the cam1 calibration");
    }
    matcher_ =
        std::make_unique<StereoMatcher>(cam0, *cam1, options.stereo_matcher);
    if (options.tracker.clahe) {
      right_clahe_ = cv::createCLAHE(
          options.tracker.clahe_clip_limit,
          cv::Size(options.tracker.clahe_tiles, options.tracker.clahe_tiles));
    }
  }
}

TrackedFrame ImageFrontend::TrackLeft(int64_t t_ns, const cv::Mat& left) {
  TrackedFrame tracked;
  tracked.frame.t_ns = t_ns;
  tracked.frame.observations = tracker_.Track(left);
  tracked.stats.tracker = tracker_.stats();
  // The left image must look to the matcher as the right one will: both
  // prepared alike (the tracker's CLAHE here, the matcher's equalisation in
  // MatchRight, off the tracking thread).
  tracked.left = tracker_.image();
  return tracked;
}

void ImageFrontend::PrepareRight(const cv::Mat& right,
                                 StereoImage* prepared) const {
  if (!matcher_ || right.empty()) {
    prepared->pyramid.clear();
    return;
  }
  if (!right_clahe_) {
    matcher_->PrepareRight(right, prepared);
    return;
  }
  cv::Mat equalised;
  right_clahe_->apply(right, equalised);
  matcher_->PrepareRight(equalised, prepared);
}

void ImageFrontend::MatchRight(const StereoImage& right,
                               TrackedFrame* tracked) {
  if (!matcher_ || right.pyramid.empty()) return;
  matcher_->PrepareLeft(tracked->left, &left_);
  const std::vector<FeatureObservation> matches = matcher_->Match(
      left_, right, tracked->frame.observations, &tracked->stats.stereo);
  tracked->frame.observations.insert(tracked->frame.observations.end(),
                                     matches.begin(), matches.end());
  tracked->stats.stereo_matched = true;
}

FeatureFrame ImageFrontend::Process(int64_t t_ns, const cv::Mat& left,
                                    const cv::Mat& right) {
  TrackedFrame tracked = TrackLeft(t_ns, left);
  PrepareRight(right, &right_);
  MatchRight(right_, &tracked);
  stats_ = tracked.stats;
  return std::move(tracked.frame);
}

}  // namespace vio
