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
    : tracker_(cam0, Validated(options).tracker, 0),
      start_from_previous_(options.stereo_matcher.start_from_previous) {
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
  if (!matcher_) return;
  if (right.pyramid.empty()) {
    previous_offset_.clear();  // no match to start from in the next frame
    return;
  }
  matcher_->PrepareLeft(tracked->left, &left_);
  std::vector<FeatureObservation>& observations = tracked->frame.observations;
  std::vector<cv::Point2f> start;
  if (start_from_previous_) {
    start.reserve(observations.size());
    for (const FeatureObservation& o : observations) {
      cv::Point2f uv(static_cast<float>(o.uv.x()),
                     static_cast<float>(o.uv.y()));
      const auto it = previous_offset_.find(o.feature_id);
      if (it != previous_offset_.end()) uv += it->second;
      start.push_back(uv);
    }
  }
  const std::vector<FeatureObservation> matches = matcher_->Match(
      left_, right, observations, start, &tracked->stats.stereo);
  if (start_from_previous_) {
    // Matches keep the order of the left observations they come from.
    previous_offset_.clear();
    size_t i = 0;
    for (const FeatureObservation& m : matches) {
      while (observations[i].feature_id != m.feature_id) ++i;
      previous_offset_[m.feature_id] =
          cv::Point2f(static_cast<float>(m.uv.x() - observations[i].uv.x()),
                      static_cast<float>(m.uv.y() - observations[i].uv.y()));
    }
  }
  observations.insert(observations.end(), matches.begin(), matches.end());
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
