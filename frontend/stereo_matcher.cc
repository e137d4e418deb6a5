#include "frontend/stereo_matcher.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "frontend/feature_tracker.h"
#include "geometry/so3.h"

namespace vio {

StereoMatcher::StereoMatcher(const CameraModel& left, const CameraModel& right,
                             const StereoMatcherOptions& options)
    : left_(left), right_(right), options_(options) {
  std::string message;
  if (!options_.Validate(&message)) {
    throw std::invalid_argument("StereoMatcherOptions: " + message);
  }
  // T_c0_c1 = T_b_c0^-1 T_b_c1: R = R_b_c0^T R_b_c1,
  // t = R_b_c0^T (t_b_c1 - t_b_c0).
  const CameraCalibration& c0 = left_.calibration();
  const CameraCalibration& c1 = right_.calibration();
  q_c0_c1_ = (c0.q_b_c.conjugate() * c1.q_b_c).normalized();
  t_c0_c1_ = c0.q_b_c.conjugate() * (c1.t_b_c - c0.t_b_c);
  essential_ = Skew(t_c0_c1_) * q_c0_c1_.toRotationMatrix();
}

void StereoMatcher::CheckImage(const cv::Mat& image, const CameraModel& camera,
                               const char* which) const {
  const CameraCalibration& c = camera.calibration();
  if (image.empty() || image.type() != CV_8UC1 || image.cols != c.width ||
      image.rows != c.height) {
    throw std::invalid_argument(
        std::string("StereoMatcher::Match: expected an 8-bit grey ") + which +
        " image of " + std::to_string(c.width) + "x" +
        std::to_string(c.height) + " (got " + std::to_string(image.cols) + "x" +
        std::to_string(image.rows) + ", type " + std::to_string(image.type()) +
        ")");
  }
}

double StereoMatcher::EpipolarErrorPx(const Eigen::Vector2d& uv0,
                                      const Eigen::Vector2d& uv1) const {
  Eigen::Vector2d xy0, xy1;
  if (!left_.PixelToNormalized(uv0, &xy0) ||
      !right_.PixelToNormalized(uv1, &xy1)) {
    return std::numeric_limits<double>::infinity();
  }
  // Line l1 = E^T f0 on the right normalised plane; point-line distance,
  // scaled by the right focal length to pixels.
  const Eigen::Vector3d l1 = essential_.transpose() * xy0.homogeneous();
  const double norm = l1.head<2>().norm();
  if (!(norm > 0.0)) return std::numeric_limits<double>::infinity();
  return std::abs(l1.dot(xy1.homogeneous())) / norm * right_.focal();
}

bool StereoMatcher::TriangulateDepth(const Eigen::Vector2d& xy0,
                                     const Eigen::Vector2d& xy1,
                                     double* depth_c0) const {
  // lambda0 f0 - lambda1 R f1 = t, two unknowns, three equations; the
  // normal equations are singular for parallel rays (a point at infinity).
  Eigen::Matrix<double, 3, 2> A;
  A.col(0) = xy0.homogeneous();
  A.col(1) = -(q_c0_c1_ * xy1.homogeneous());
  const Eigen::Matrix2d AtA = A.transpose() * A;
  if (!(std::abs(AtA.determinant()) > 1e-12)) return false;
  const Eigen::Vector2d lambda = AtA.inverse() * (A.transpose() * t_c0_c1_);
  if (!(lambda[0] > 0.0 && lambda[1] > 0.0)) return false;
  *depth_c0 = lambda[0];  // f0 has z = 1, so lambda0 is the depth
  return true;
}

void StereoMatcher::Prepare(const cv::Mat& image, StereoImage* prepared) const {
  if (options_.equalize) {
    cv::equalizeHist(image, prepared->equalised);
    BuildKltPyramid(prepared->equalised, options_.klt, &prepared->pyramid);
  } else {
    BuildKltPyramid(image, options_.klt, &prepared->pyramid);
  }
}

StereoImage StereoMatcher::PrepareLeft(const cv::Mat& image) const {
  StereoImage prepared;
  PrepareLeft(image, &prepared);
  return prepared;
}

StereoImage StereoMatcher::PrepareRight(const cv::Mat& image) const {
  StereoImage prepared;
  PrepareRight(image, &prepared);
  return prepared;
}

void StereoMatcher::PrepareLeft(const cv::Mat& image,
                                StereoImage* prepared) const {
  CheckImage(image, left_, "left");
  Prepare(image, prepared);
}

void StereoMatcher::PrepareRight(const cv::Mat& image,
                                 StereoImage* prepared) const {
  CheckImage(image, right_, "right");
  Prepare(image, prepared);
}

std::vector<FeatureObservation> StereoMatcher::Match(
    const cv::Mat& left, const cv::Mat& right,
    const std::vector<FeatureObservation>& left_observations,
    StereoStats* stats) const {
  const StereoImage prepared_left = PrepareLeft(left);
  return Match(prepared_left, PrepareRight(right), left_observations, stats);
}

std::vector<FeatureObservation> StereoMatcher::Match(
    const StereoImage& left, const StereoImage& right,
    const std::vector<FeatureObservation>& left_observations,
    StereoStats* stats) const {
  return Match(left, right, left_observations, {}, stats);
}

std::vector<FeatureObservation> StereoMatcher::Match(
    const StereoImage& left, const StereoImage& right,
    const std::vector<FeatureObservation>& left_observations,
    const std::vector<cv::Point2f>& start, StereoStats* stats) const {
  if (!start.empty() && start.size() != left_observations.size()) {
    throw std::invalid_argument(
        "StereoMatcher::Match: " + std::to_string(start.size()) +
        " start pixels for " + std::to_string(left_observations.size()) +
        " left observations");
  }
  StereoStats counts;
  std::vector<FeatureObservation> matches;
  std::vector<cv::Point2f> uv0;
  uv0.reserve(left_observations.size());
  for (const FeatureObservation& o : left_observations) {
    uv0.emplace_back(static_cast<float>(o.uv.x()),
                     static_cast<float>(o.uv.y()));
  }
  std::vector<cv::Point2f> uv1, back;
  std::vector<uchar> ok, ok_back;
  // OpenCV starts a point without a guess at its own position, so a start
  // equal to the left pixel gives the unguided match bit for bit.
  TrackKlt(left.pyramid, right.pyramid, options_.klt, uv0, start, &uv1, &ok);
  KltOptions reverse = options_.klt;
  reverse.pyramid_levels = options_.reverse_pyramid_levels;
  TrackKlt(right.pyramid, left.pyramid, reverse, uv1, uv0, &back, &ok_back);

  const double max_reverse2 = options_.max_reverse_px * options_.max_reverse_px;
  const int w = right_.calibration().width, h = right_.calibration().height;
  for (size_t i = 0; i < uv0.size(); ++i) {
    const Eigen::Vector2d p0(uv0[i].x, uv0[i].y), p1(uv1[i].x, uv1[i].y);
    if (!ok[i] ||
        !(p1.x() >= 0.0 && p1.y() >= 0.0 && p1.x() < w && p1.y() < h)) {
      ++counts.lost_flow;
      continue;
    }
    const cv::Point2f d = back[i] - uv0[i];
    if (!ok_back[i] || d.dot(d) > max_reverse2) {
      ++counts.lost_reverse;
      continue;
    }
    if (!(EpipolarErrorPx(p0, p1) <= options_.max_epipolar_px)) {
      ++counts.rejected_epipolar;
      continue;
    }
    Eigen::Vector2d xy0, xy1;
    double depth = 0.0;
    if (!left_.PixelToNormalized(p0, &xy0) ||
        !right_.PixelToNormalized(p1, &xy1) ||
        !TriangulateDepth(xy0, xy1, &depth)) {
      ++counts.rejected_depth;
      continue;
    }
    FeatureObservation o;
    o.feature_id = left_observations[i].feature_id;
    o.camera = 1;
    o.uv = p1;
    matches.push_back(o);
  }
  counts.matched = static_cast<int>(matches.size());
  if (stats) *stats = counts;
  return matches;
}

}  // namespace vio
