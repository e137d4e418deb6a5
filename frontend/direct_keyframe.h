#ifndef VIO_FRONTEND_DIRECT_KEYFRAME_H_
#define VIO_FRONTEND_DIRECT_KEYFRAME_H_

// A keyframe of the direct method: its left image pyramid and a semi-dense
// inverse-depth map with variances (frontend/stereo_depth.h) on every
// pyramid level from the one the depth was computed at up to the coarsest.
//
// Coarser levels (LSD-SLAM's depth-map pyramid): a pixel of level l + 1
// covers a 2 x 2 block of level l; it takes the inverse-variance weighted
// mean of the block's points,
//   rho = sum(rho_k / V_k) / sum(1 / V_k),
//   V   = n / sum(1 / V_k) + sum(w_k (rho_k - rho)^2) / sum(w_k),  w_k = 1/V_k
// i.e. the harmonic mean of the variances (neighbouring matches share image
// data, so no gain is claimed for averaging them) plus their spread (a block
// across a depth edge is uncertain). Its intensity is the level's own pixel.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "frontend/image_pyramid.h"
#include "frontend/stereo_depth.h"

namespace vio {

struct DirectKeyframe {
  int64_t t_ns = 0;
  ImagePyramid image;  // the keyframe's left image
  // points[l]: the depth points of pyramid level l (empty below the level
  // the depth was computed at).
  std::vector<std::vector<DepthPoint>> points;
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();  // its left camera
  double median_depth_m = 0.0;  // of the depth level's points [m]
};

// Builds the keyframe from the depth points of pyramid level `level` of
// `image`. Throws std::invalid_argument when level is not a level of image.
DirectKeyframe MakeDirectKeyframe(int64_t t_ns, const ImagePyramid& image,
                                  std::vector<DepthPoint> points, int level);

// The points of the next coarser level (header comment), with intensities
// from `coarser`, the pyramid level they belong to.
std::vector<DepthPoint> CoarserDepthPoints(
    const std::vector<DepthPoint>& points, const PyramidLevel& coarser);

}  // namespace vio

#endif  // VIO_FRONTEND_DIRECT_KEYFRAME_H_
