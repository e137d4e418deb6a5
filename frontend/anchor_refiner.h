#ifndef VIO_FRONTEND_ANCHOR_REFINER_H_
#define VIO_FRONTEND_ANCHOR_REFINER_H_

// Drift-free KLT: each track's frame-to-frame position is refined against
// the track's own first appearance (its anchor patch) with an affine warp,
// so that its error neither adds up from frame to frame nor grows as the
// patch deforms.
//
// Why (docs/rendering.md, rendered sequences with exact truth): pyramidal
// LK estimates a translation only. When a patch is scaled or turned (the
// camera approaches a wall, rolls, or carries the patch towards the
// strongly distorted image border) the translation that best aligns it is
// not the motion of its centre but that of its gradient-weighted texture,
// and the track slides: its error against the first sighting grew from
// 0.06 px after one frame to 0.54 px after 40 frames (0.34 px under pure
// rotation), and refining the translation against the first appearance did
// not help. An affine warp follows the deformation, so the centre stays on
// its point.
//
// How: inverse-compositional affine Lucas-Kanade (Baker and Matthews,
// "Lucas-Kanade 20 years on", IJCV 2004, section 3.2) on a window_px square
// patch at pyramid level 0. The warp maps a patch offset x (from the patch
// centre) to the image point W(x) = M x + t; t is the track's position.
// The anchor's steepest-descent images and Hessian are computed once, when
// the track starts; each iteration samples the image under the current
// warp (cv::warpAffine), normalises its mean and contrast to the anchor's
// (exposure and vignetting change along a track), and composes the inverse
// of the solved increment. OpenCV's cv::findTransformECC solves the same
// alignment but took 0.33 ms per patch here, ten times more.
//
// A refinement is accepted when it converges, moves the point by at most
// anchor_max_correction_px from its frame-to-frame position, keeps the warp
// within a factor 2 of the anchor's scale, and the warped patch correlates
// with the anchor by at least anchor_min_correlation (zero-mean normalised
// cross-correlation). Below that correlation the patch no longer shows the
// anchor's point (an occlusion, a corner between two surfaces): the track
// is dropped. Otherwise a refused refinement keeps the frame-to-frame
// position and renews the anchor there.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <vector>

#include "frontend/frontend_options.h"

namespace vio {

// The 32-bit float grey `image` under the affine warp W(x) = M x + t over
// the square patch of offsets x = (j - half, i - half), i, j in
// [0, 2 half], into *samples (row-major, (2 half + 1)^2 values): bilinear,
// the borders clamped (a point beyond the image reads its nearest edge).
// Each point is computed as (M00 x0 + M01 x1) + t0, (M10 x0 + M11 x1) + t1
// and each sample as one fixed sequence of float operations, so the result
// is bit for bit that of the plain per-pixel expressions (and of the
// refiner before this function was made faster). `buffer` holds the warp's
// products between calls.
void SampleAffinePatch(const cv::Mat& image, const Eigen::Matrix2f& M,
                       const Eigen::Vector2f& t, int half,
                       std::vector<float>* buffer, Eigen::VectorXf* samples);

// What AnchorRefiner::Refine did with each track.
enum class AnchorResult : uint8_t { kRefined, kRenewed, kDropped };

class AnchorRefiner {
 public:
  // Uses options.klt (window side, iterations, epsilon) and the anchor_*
  // options.
  explicit AnchorRefiner(const FeatureTrackerOptions& options);

  // Stores the anchor of track `id` at `uv` in `image` (8-bit grey or
  // 32-bit float), with an identity warp.
  void Add(int64_t id, const cv::Mat& image, const cv::Point2f& uv);

  // Refines points[i] (track ids[i], each with an anchor) in `image`
  // (32-bit float grey, the same image the anchors were cut from, converted
  // once per frame by the caller) and returns what happened to each.
  std::vector<AnchorResult> Refine(const cv::Mat& image,
                                   const std::vector<int64_t>& ids,
                                   std::vector<cv::Point2f>* points);

  // Forgets the anchors of tracks not in `ids`.
  void Keep(const std::vector<int64_t>& ids);
  void Clear() { anchors_.clear(); }

 private:
  static constexpr int kParams = 6;  // d M (4, row-major), d t (2)
  using SteepestDescent = Eigen::Matrix<float, Eigen::Dynamic, kParams>;
  struct Anchor {
    Eigen::VectorXf patch;  // the anchor's pixels, row-major, zero mean
    float contrast = 0.0f;  // their standard deviation [grey levels]
    SteepestDescent sd;     // grad T . dW/dp per pixel
    Eigen::Matrix<float, kParams, kParams> hessian_inverse;
    Eigen::Matrix2f M = Eigen::Matrix2f::Identity();  // the current warp
    bool usable = false;  // false: too flat to align
  };
  // Aligns anchor `a` with the image from position t; true when it
  // converged with a sane warp. Sets the aligned position and correlation.
  bool Align(const cv::Mat& image, Anchor* a, Eigen::Vector2f* t,
             float* correlation);

  FeatureTrackerOptions options_;
  int half_;  // patch half side [px]
  std::unordered_map<int64_t, Anchor> anchors_;
  // Align's buffers, kept from call to call (SampleAffinePatch's and the
  // samples).
  std::vector<float> offsets_;
  Eigen::VectorXf sample_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_ANCHOR_REFINER_H_
