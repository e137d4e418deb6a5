#include "frontend/feature_tracker.h"

#include <algorithm>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

// Keeps the entries of `v` whose `keep` flag is set, in order.
template <typename T>
void Compact(const std::vector<uchar>& keep, std::vector<T>* v) {
  size_t j = 0;
  for (size_t i = 0; i < v->size(); ++i) {
    if (keep[i]) (*v)[j++] = (*v)[i];
  }
  v->resize(j);
}

int CountZeros(const std::vector<uchar>& flags) {
  return static_cast<int>(std::count(flags.begin(), flags.end(), 0));
}

}  // namespace

std::vector<cv::Mat> BuildKltPyramid(const cv::Mat& image,
                                     const KltOptions& klt) {
  std::vector<cv::Mat> pyramid;
  BuildKltPyramid(image, klt, &pyramid);
  return pyramid;
}

void BuildKltPyramid(const cv::Mat& image, const KltOptions& klt,
                     std::vector<cv::Mat>* pyramid) {
  cv::buildOpticalFlowPyramid(image, *pyramid,
                              cv::Size(klt.window_px, klt.window_px),
                              klt.pyramid_levels, true);
}

void TrackKlt(cv::InputArray from, cv::InputArray to, const KltOptions& klt,
              const std::vector<cv::Point2f>& points,
              const std::vector<cv::Point2f>& guess,
              std::vector<cv::Point2f>* tracked, std::vector<uchar>* ok) {
  if (points.empty()) {
    tracked->clear();
    ok->clear();
    return;
  }
  std::vector<float> error;
  const cv::TermCriteria criteria(
      cv::TermCriteria::COUNT | cv::TermCriteria::EPS, klt.max_iterations,
      klt.epsilon_px);
  int flags = 0;
  if (!guess.empty()) {
    *tracked = guess;
    flags = cv::OPTFLOW_USE_INITIAL_FLOW;
  }
  cv::calcOpticalFlowPyrLK(from, to, points, *tracked, *ok, error,
                           cv::Size(klt.window_px, klt.window_px),
                           klt.pyramid_levels, criteria, flags);
}

std::vector<uchar> FundamentalInliers(const CameraModel& camera,
                                      const std::vector<cv::Point2f>& prev_uv,
                                      const std::vector<cv::Point2f>& curr_uv,
                                      const FeatureTrackerOptions& options) {
  const size_t n = prev_uv.size();
  std::vector<uchar> inlier(n, 1);
  // Undistort, then back to pixels of a virtual distortion-free pinhole, so
  // that the RANSAC threshold means the same for every camera.
  const double f = options.virtual_focal_px;
  const double cx = 0.5 * camera.calibration().width;
  const double cy = 0.5 * camera.calibration().height;
  std::vector<cv::Point2f> prev_virtual, curr_virtual;
  std::vector<size_t> index;
  for (size_t i = 0; i < n; ++i) {
    Eigen::Vector2d xy_prev, xy_curr;
    if (!camera.PixelToNormalized({prev_uv[i].x, prev_uv[i].y}, &xy_prev) ||
        !camera.PixelToNormalized({curr_uv[i].x, curr_uv[i].y}, &xy_curr)) {
      inlier[i] = 0;
      continue;
    }
    prev_virtual.emplace_back(f * xy_prev.x() + cx, f * xy_prev.y() + cy);
    curr_virtual.emplace_back(f * xy_curr.x() + cx, f * xy_curr.y() + cy);
    index.push_back(i);
  }
  if (index.size() < 8) return inlier;
  std::vector<uchar> mask;
  const cv::Mat F = cv::findFundamentalMat(
      prev_virtual, curr_virtual, cv::FM_RANSAC,
      options.fundamental_threshold_px, options.fundamental_confidence, mask);
  // No model (RANSAC failed outright): nothing can be judged.
  if (F.empty() || mask.size() != index.size()) return inlier;
  for (size_t k = 0; k < index.size(); ++k) inlier[index[k]] = mask[k];
  return inlier;
}

FeatureTracker::FeatureTracker(const CameraModel& camera,
                               const FeatureTrackerOptions& options,
                               int camera_index)
    : camera_(camera),
      options_(options),
      camera_index_(camera_index),
      anchors_(options) {
  std::string message;
  if (!options_.Validate(&message)) {
    throw std::invalid_argument("FeatureTrackerOptions: " + message);
  }
  if (options_.clahe) {
    clahe_ =
        cv::createCLAHE(options_.clahe_clip_limit,
                        cv::Size(options_.clahe_tiles, options_.clahe_tiles));
  }
}

cv::Mat FeatureTracker::Preprocess(const cv::Mat& image) const {
  if (!clahe_) return image;
  cv::Mat equalised;
  clahe_->apply(image, equalised);
  return equalised;
}

void FeatureTracker::Reset() {
  image_.release();
  pyramid_.clear();
  points_.clear();
  ids_.clear();
  ages_.clear();
  anchors_.Clear();
  history_.clear();
}

bool FeatureTracker::InsideBorder(const cv::Point2f& uv) const {
  const float b = static_cast<float>(options_.border_px);
  return uv.x >= b && uv.y >= b && uv.x < camera_.calibration().width - b &&
         uv.y < camera_.calibration().height - b;
}

std::vector<FeatureObservation> FeatureTracker::Track(const cv::Mat& image) {
  const CameraCalibration& c = camera_.calibration();
  if (image.empty() || image.type() != CV_8UC1 || image.cols != c.width ||
      image.rows != c.height) {
    throw std::invalid_argument(
        "FeatureTracker::Track: expected an 8-bit grey " +
        std::to_string(c.width) + "x" + std::to_string(c.height) +
        " image (got " + std::to_string(image.cols) + "x" +
        std::to_string(image.rows) + ", type " + std::to_string(image.type()) +
        ")");
  }
  stats_ = TrackerStats();
  const cv::Mat current = Preprocess(image);
  // Into the buffers of the pyramid before the previous one: the same size
  // every frame, so no allocation (and no page faults) after the second.
  BuildKltPyramid(current, options_.klt, &spare_pyramid_);
  if (!pyramid_.empty()) TrackFromPrevious(current, spare_pyramid_);
  Refill(current);
  image_ = current;
  std::swap(pyramid_, spare_pyramid_);

  std::vector<FeatureObservation> observations(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) {
    observations[i].feature_id = ids_[i];
    observations[i].camera = camera_index_;
    observations[i].uv = Eigen::Vector2d(points_[i].x, points_[i].y);
  }
  return observations;
}

void FeatureTracker::TrackFromPrevious(const cv::Mat& image,
                                       const std::vector<cv::Mat>& pyramid) {
  if (points_.empty()) return;
  std::vector<cv::Point2f> forward, backward;
  std::vector<uchar> ok, ok_back;
  TrackKlt(pyramid_, pyramid, options_.klt, points_, {}, &forward, &ok);
  for (size_t i = 0; i < ok.size(); ++i) {
    if (ok[i] && !InsideBorder(forward[i])) ok[i] = 0;
  }
  stats_.lost_flow = CountZeros(ok);
  Compact(ok, &points_);
  Compact(ok, &forward);
  Compact(ok, &ids_);
  Compact(ok, &ages_);

  // Forward-backward: a good track, followed back, returns to its start.
  TrackKlt(pyramid, pyramid_, options_.klt, forward, points_, &backward,
           &ok_back);
  const double max_fb2 =
      options_.max_forward_backward_px * options_.max_forward_backward_px;
  for (size_t i = 0; i < ok_back.size(); ++i) {
    const cv::Point2f d = backward[i] - points_[i];
    if (ok_back[i] && d.dot(d) > max_fb2) ok_back[i] = 0;
  }
  stats_.lost_forward_backward = CountZeros(ok_back);
  Compact(ok_back, &points_);
  Compact(ok_back, &forward);
  Compact(ok_back, &ids_);
  Compact(ok_back, &ages_);

  if (options_.anchor_refinement) {
    image.convertTo(image_float_, CV_32F);
    const std::vector<AnchorResult> results =
        anchors_.Refine(image_float_, ids_, &forward);
    std::vector<uchar> keep(results.size(), 1);
    for (size_t i = 0; i < results.size(); ++i) {
      if (results[i] == AnchorResult::kRenewed) ++stats_.reanchored;
      if (results[i] == AnchorResult::kDropped) keep[i] = 0;
    }
    stats_.lost_anchor = CountZeros(keep);
    Compact(keep, &points_);
    Compact(keep, &forward);
    Compact(keep, &ids_);
    Compact(keep, &ages_);
  }
  if (options_.fundamental_check) {
    const std::vector<uchar> inlier =
        FundamentalInliers(camera_, points_, forward, options_);
    stats_.rejected_fundamental = CountZeros(inlier);
    Compact(inlier, &forward);
    Compact(inlier, &ids_);
    Compact(inlier, &ages_);
  }
  points_ = std::move(forward);
  for (int& age : ages_) ++age;
  if (options_.fundamental_check && options_.fundamental_baseline_frames > 0) {
    CheckLongBaseline();
  }
}

void FeatureTracker::CheckLongBaseline() {
  if (static_cast<int>(history_.size()) <
      options_.fundamental_baseline_frames) {
    return;
  }
  const std::unordered_map<int64_t, cv::Point2f>& then = history_.front();
  std::vector<cv::Point2f> before, now;
  std::vector<size_t> index;
  for (size_t i = 0; i < ids_.size(); ++i) {
    const auto it = then.find(ids_[i]);
    if (it == then.end()) continue;
    before.push_back(it->second);
    now.push_back(points_[i]);
    index.push_back(i);
  }
  const std::vector<uchar> inlier =
      FundamentalInliers(camera_, before, now, options_);
  std::vector<uchar> keep(ids_.size(), 1);
  for (size_t k = 0; k < index.size(); ++k) keep[index[k]] = inlier[k];
  stats_.rejected_baseline = CountZeros(keep);
  Compact(keep, &points_);
  Compact(keep, &ids_);
  Compact(keep, &ages_);
}

void FeatureTracker::Refill(const cv::Mat& image) {
  // Older tracks first: they claim their neighbourhood, and a younger track
  // inside it is dropped (it would add little but correlated information).
  std::vector<size_t> order(points_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return ages_[a] > ages_[b]; });
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  const int radius = static_cast<int>(std::round(options_.min_distance_px));
  std::vector<cv::Point2f> points;
  std::vector<int64_t> ids;
  std::vector<int> ages;
  for (size_t i : order) {
    const cv::Point pixel(std::clamp(cvRound(points_[i].x), 0, mask.cols - 1),
                          std::clamp(cvRound(points_[i].y), 0, mask.rows - 1));
    if (mask.at<uchar>(pixel) == 0) {
      ++stats_.dropped_crowded;
      continue;
    }
    if (radius > 0) cv::circle(mask, pixel, radius, cv::Scalar(0), cv::FILLED);
    points.push_back(points_[i]);
    ids.push_back(ids_[i]);
    ages.push_back(ages_[i]);
    ++stats_.tracked;
  }
  const int wanted = options_.max_features - static_cast<int>(points.size());
  if (wanted >= options_.refill_min_missing) {
    const std::vector<cv::Point2f> corners = detector_.Detect(
        image, mask, wanted, options_.corner_quality, options_.min_distance_px);
    for (const cv::Point2f& corner : corners) {
      if (!InsideBorder(corner)) continue;
      points.push_back(corner);
      if (options_.anchor_refinement) anchors_.Add(next_id_, image, corner);
      ids.push_back(next_id_++);
      ages.push_back(1);
      ++stats_.created;
    }
  }
  points_ = std::move(points);
  ids_ = std::move(ids);
  ages_ = std::move(ages);
  if (options_.anchor_refinement) anchors_.Keep(ids_);
  if (options_.fundamental_baseline_frames > 0) {
    std::unordered_map<int64_t, cv::Point2f> positions;
    for (size_t i = 0; i < ids_.size(); ++i) positions[ids_[i]] = points_[i];
    history_.push_back(std::move(positions));
    while (static_cast<int>(history_.size()) >
           options_.fundamental_baseline_frames) {
      history_.pop_front();
    }
  }
}

}  // namespace vio
