#include "frontend/anchor_refiner.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_set>

namespace vio {
namespace {

// The smallest anchor contrast worth aligning [grey levels], and the
// smallest eigenvalue of the translation block of the Gauss-Newton matrix
// per pixel [grey^2/px^2]: below, the patch is too flat to be located.
constexpr float kMinContrast = 2.0f;
constexpr float kMinTranslationInformation = 1.0f;
// A refinement that has not settled to this step is not converged [px].
constexpr float kMaxFinalStepPx = 0.05f;
// The warp may scale the anchor by at most this factor either way.
constexpr float kMaxScale = 2.0f;

// Bilinear sample of a 32-bit float image, borders clamped.
float Bilinear(const cv::Mat& image, float u, float v) {
  u = std::clamp(u, 0.0f, static_cast<float>(image.cols - 1));
  v = std::clamp(v, 0.0f, static_cast<float>(image.rows - 1));
  const int x = std::min(static_cast<int>(u), image.cols - 2);
  const int y = std::min(static_cast<int>(v), image.rows - 2);
  const float a = u - x, b = v - y;
  const float* r0 = image.ptr<float>(y) + x;
  const float* r1 = image.ptr<float>(y + 1) + x;
  return (1 - b) * ((1 - a) * r0[0] + a * r0[1]) +
         b * ((1 - a) * r1[0] + a * r1[1]);
}

}  // namespace

AnchorRefiner::AnchorRefiner(const FeatureTrackerOptions& options)
    : options_(options), half_((options.klt.window_px - 1) / 2) {}

void AnchorRefiner::Add(int64_t id, const cv::Mat& image,
                        const cv::Point2f& uv) {
  const int side = 2 * half_ + 1;
  // One pixel more on each side for the central-difference gradients.
  cv::Mat p;
  cv::getRectSubPix(image, cv::Size(side + 2, side + 2), uv, p, CV_32F);
  Anchor a;
  a.patch.resize(side * side);
  a.sd.resize(side * side, kParams);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int k = i * side + j;
      const float gx =
          0.5f * (p.at<float>(i + 1, j + 2) - p.at<float>(i + 1, j));
      const float gy =
          0.5f * (p.at<float>(i + 2, j + 1) - p.at<float>(i, j + 1));
      const float x = static_cast<float>(j - half_);
      const float y = static_cast<float>(i - half_);
      a.patch[k] = p.at<float>(i + 1, j + 1);
      // grad T . dW/dp at p = 0, W(x) = (I + D) x + d: the parameters are
      // D00, D01, D10, D11, d0, d1.
      a.sd.row(k) << gx * x, gx * y, gy * x, gy * y, gx, gy;
    }
  }
  a.patch.array() -= a.patch.mean();
  a.contrast = std::sqrt(a.patch.squaredNorm() / a.patch.size());
  const Eigen::Matrix<float, kParams, kParams> H = a.sd.transpose() * a.sd;
  const Eigen::Matrix2f H_t = H.bottomRightCorner<2, 2>();
  const float min_eigen =
      0.5f * (H_t.trace() -
              std::sqrt((H_t(0, 0) - H_t(1, 1)) * (H_t(0, 0) - H_t(1, 1)) +
                        4 * H_t(0, 1) * H_t(0, 1)));
  a.usable = a.contrast >= kMinContrast &&
             min_eigen >= kMinTranslationInformation * a.patch.size();
  if (a.usable) {
    a.hessian_inverse =
        H.cast<double>()
            .ldlt()
            .solve(Eigen::Matrix<double, kParams, kParams>::Identity())
            .cast<float>();
  }
  anchors_[id] = std::move(a);
}

Eigen::VectorXf AnchorRefiner::Sample(const cv::Mat& image,
                                      const Eigen::Matrix2f& M,
                                      const Eigen::Vector2f& t) const {
  const int side = 2 * half_ + 1;
  Eigen::VectorXf s(side * side);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const Eigen::Vector2f q =
          M * Eigen::Vector2f(static_cast<float>(j - half_),
                              static_cast<float>(i - half_)) +
          t;
      s[i * side + j] = Bilinear(image, q.x(), q.y());
    }
  }
  return s;
}

bool AnchorRefiner::Align(const cv::Mat& image, Anchor* a, Eigen::Vector2f* t,
                          float* correlation) const {
  Eigen::Matrix2f M = a->M;
  Eigen::Vector2f position = *t;
  float step = 1e9f;
  const int n = static_cast<int>(a->patch.size());
  for (int iteration = 0; iteration < options_.klt.max_iterations;
       ++iteration) {
    Eigen::VectorXf s = Sample(image, M, position);
    s.array() -= s.mean();
    const float contrast = std::sqrt(s.squaredNorm() / n);
    if (contrast < 1e-3f) break;
    // The sample brought to the anchor's contrast (both are zero-mean).
    const Eigen::VectorXf e = s * (a->contrast / contrast) - a->patch;
    const Eigen::Matrix<float, kParams, 1> dp =
        a->hessian_inverse * (a->sd.transpose() * e);
    // Inverse composition W <- W o W(dp)^-1, W(dp)(x) = (I + D) x + d:
    // M <- M (I + D)^-1, t <- t - M (I + D)^-1 d.
    Eigen::Matrix2f I_D;
    I_D << 1 + dp[0], dp[1], dp[2], 1 + dp[3];
    const Eigen::Matrix2f M_new = M * I_D.inverse();
    const Eigen::Vector2f shift = M_new * dp.tail<2>();
    M = M_new;
    position -= shift;
    step = shift.norm();
    if (!M.allFinite() || !position.allFinite()) return false;
    if (step < options_.klt.epsilon_px) break;
  }
  Eigen::VectorXf s = Sample(image, M, position);
  s.array() -= s.mean();
  const float contrast = std::sqrt(s.squaredNorm() / n);
  *correlation =
      contrast > 1e-3f ? s.dot(a->patch) / (n * contrast * a->contrast) : 0.0f;
  const Eigen::Vector2f sv = M.jacobiSvd().singularValues();
  if (step > kMaxFinalStepPx || sv[0] > kMaxScale || sv[1] < 1 / kMaxScale) {
    return false;
  }
  a->M = M;
  *t = position;
  return true;
}

std::vector<AnchorResult> AnchorRefiner::Refine(
    const cv::Mat& image, const std::vector<int64_t>& ids,
    std::vector<cv::Point2f>* points) {
  std::vector<AnchorResult> results(ids.size(), AnchorResult::kRefined);
  const float max_correction =
      static_cast<float>(options_.anchor_max_correction_px);
  for (size_t i = 0; i < ids.size(); ++i) {
    cv::Point2f& point = (*points)[i];
    Anchor& a = anchors_.at(ids[i]);
    Eigen::Vector2f t(point.x, point.y);
    float correlation = 0.0f;
    const Eigen::Matrix2f M = a.M;
    const bool aligned = a.usable && Align(image, &a, &t, &correlation);
    if (a.usable &&
        correlation < static_cast<float>(options_.anchor_min_correlation)) {
      results[i] = AnchorResult::kDropped;
    } else if (aligned && (t - Eigen::Vector2f(point.x, point.y)).norm() <=
                              max_correction) {
      point = cv::Point2f(t.x(), t.y());
    } else {
      a.M = M;
      Add(ids[i], image, point);
      results[i] = AnchorResult::kRenewed;
    }
  }
  return results;
}

void AnchorRefiner::Keep(const std::vector<int64_t>& ids) {
  const std::unordered_set<int64_t> alive(ids.begin(), ids.end());
  for (auto it = anchors_.begin(); it != anchors_.end();) {
    it = alive.count(it->first) ? std::next(it) : anchors_.erase(it);
  }
}

}  // namespace vio
