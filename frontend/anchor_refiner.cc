#include "frontend/anchor_refiner.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <unordered_set>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// Sample's inner loop over one patch row, four pixels per step where the
// processor has SSE2: the same IEEE single-precision operations in the same
// order per lane as the scalar loop (no fused multiply-add), so the same
// bits. Samples row[j] for j from 0 while j + 4 <= side and returns the
// first j not sampled (0 without SSE2).
int SampleFourAtATime(const float* data, size_t step, const float* column_u,
                      const float* column_v, float row_u, float row_v,
                      const Eigen::Vector2f& t, int side, float* row) {
  int j = 0;
#if defined(__SSE2__)
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 ru = _mm_set1_ps(row_u), rv = _mm_set1_ps(row_v);
  const __m128 tu = _mm_set1_ps(t.x()), tv = _mm_set1_ps(t.y());
  alignas(16) int xs[4], ys[4];
  for (; j + 4 <= side; j += 4) {
    const __m128 u = _mm_add_ps(_mm_add_ps(_mm_loadu_ps(column_u + j), ru), tu);
    const __m128 v = _mm_add_ps(_mm_add_ps(_mm_loadu_ps(column_v + j), rv), tv);
    const __m128i x = _mm_cvttps_epi32(u), y = _mm_cvttps_epi32(v);
    const __m128 a = _mm_sub_ps(u, _mm_cvtepi32_ps(x));
    const __m128 b = _mm_sub_ps(v, _mm_cvtepi32_ps(y));
    _mm_store_si128(reinterpret_cast<__m128i*>(xs), x);
    _mm_store_si128(reinterpret_cast<__m128i*>(ys), y);
    const float* p[4];
    for (int k = 0; k < 4; ++k) p[k] = data + ys[k] * step + xs[k];
    const __m128 r00 = _mm_setr_ps(p[0][0], p[1][0], p[2][0], p[3][0]);
    const __m128 r01 = _mm_setr_ps(p[0][1], p[1][1], p[2][1], p[3][1]);
    const __m128 r10 =
        _mm_setr_ps(p[0][step], p[1][step], p[2][step], p[3][step]);
    const __m128 r11 = _mm_setr_ps(p[0][step + 1], p[1][step + 1],
                                   p[2][step + 1], p[3][step + 1]);
    const __m128 one_a = _mm_sub_ps(one, a), one_b = _mm_sub_ps(one, b);
    const __m128 top = _mm_add_ps(_mm_mul_ps(one_a, r00), _mm_mul_ps(a, r01));
    const __m128 bottom =
        _mm_add_ps(_mm_mul_ps(one_a, r10), _mm_mul_ps(a, r11));
    _mm_storeu_ps(row + j,
                  _mm_add_ps(_mm_mul_ps(one_b, top), _mm_mul_ps(b, bottom)));
  }
#else
  (void)data, (void)step, (void)column_u, (void)column_v, (void)row_u;
  (void)row_v, (void)t, (void)side, (void)row;
#endif
  return j;
}

}  // namespace

void SampleAffinePatch(const cv::Mat& image, const Eigen::Matrix2f& M,
                       const Eigen::Vector2f& t, int half,
                       std::vector<float>* buffer, Eigen::VectorXf* samples) {
  // The point of pixel (i, j) is q = M (x, y) + t with x = j - half,
  // y = i - half, in this order of float operations: (M00 x + M01 y) + t0,
  // (M10 x + M11 y) + t1, as Eigen's product computes it. The products are
  // taken once per column and row, the sums per pixel, so every q is the
  // one the plain product gives, bit for bit.
  const int side = 2 * half + 1;
  buffer->resize(4 * side);
  float* column_u = buffer->data();
  float* column_v = column_u + side;
  float* row_u = column_v + side;
  float* row_v = row_u + side;
  for (int k = 0; k < side; ++k) {
    const float o = static_cast<float>(k - half);
    column_u[k] = M(0, 0) * o;
    column_v[k] = M(1, 0) * o;
    row_u[k] = M(0, 1) * o;
    row_v[k] = M(1, 1) * o;
  }
  samples->resize(side * side);
  float* s = samples->data();
  // The patch's points are within the convex hull of its four corners, up
  // to a few float roundings (< 1e-3 px at these magnitudes). With the
  // corners 1 px inside [0, cols - 1) x [0, rows - 1), Bilinear's clamps
  // change nothing: its arithmetic runs without them, the same operations.
  float u_min = std::numeric_limits<float>::infinity(), u_max = -u_min;
  float v_min = u_min, v_max = -u_min;
  for (int i : {0, side - 1}) {
    for (int j : {0, side - 1}) {
      const float u = (column_u[j] + row_u[i]) + t.x();
      const float v = (column_v[j] + row_v[i]) + t.y();
      u_min = std::min(u_min, u);
      u_max = std::max(u_max, u);
      v_min = std::min(v_min, v);
      v_max = std::max(v_max, v);
    }
  }
  if (!(u_min >= 1.0f && v_min >= 1.0f &&
        u_max < static_cast<float>(image.cols - 2) &&
        v_max < static_cast<float>(image.rows - 2))) {
    for (int i = 0; i < side; ++i) {
      for (int j = 0; j < side; ++j) {
        s[i * side + j] = Bilinear(image, (column_u[j] + row_u[i]) + t.x(),
                                   (column_v[j] + row_v[i]) + t.y());
      }
    }
    return;
  }
  const size_t step = image.step1();
  const float* data = image.ptr<float>();
  for (int i = 0; i < side; ++i) {
    float* row = s + i * side;
    int j = SampleFourAtATime(data, step, column_u, column_v, row_u[i],
                              row_v[i], t, side, row);
    for (; j < side; ++j) {
      const float u = (column_u[j] + row_u[i]) + t.x();
      const float v = (column_v[j] + row_v[i]) + t.y();
      const int x = static_cast<int>(u), y = static_cast<int>(v);
      const float a = u - x, b = v - y;
      const float* r0 = data + y * step + x;
      const float* r1 = r0 + step;
      row[j] = (1 - b) * ((1 - a) * r0[0] + a * r0[1]) +
               b * ((1 - a) * r1[0] + a * r1[1]);
    }
  }
}

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

bool AnchorRefiner::Align(const cv::Mat& image, Anchor* a, Eigen::Vector2f* t,
                          float* correlation) {
  Eigen::Matrix2f M = a->M;
  Eigen::Vector2f position = *t;
  float step = 1e9f;
  const int n = static_cast<int>(a->patch.size());
  Eigen::VectorXf& s = sample_;
  for (int iteration = 0; iteration < options_.klt.max_iterations;
       ++iteration) {
    SampleAffinePatch(image, M, position, half_, &offsets_, &s);
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
  SampleAffinePatch(image, M, position, half_, &offsets_, &s);
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
