#ifndef VIO_FRONTEND_STEREO_DEPTH_H_
#define VIO_FRONTEND_STEREO_DEPTH_H_

// Semi-dense inverse depth of a keyframe's left image from its calibrated
// stereo pair, in the manner of LSD-SLAM's stereo search (J. Engel, J. Sturm,
// D. Cremers, "Semi-Dense Visual Odometry for a Monocular Camera", ICCV 2013,
// sec. 2.1-2.2), on undistorted pinhole images of one pyramid level:
//
// 1. Pixels whose gradient is strong (min_gradient) and not too
//    perpendicular to the epipolar line (min_line_cosine) are candidates: an
//    edge parallel to the line cannot say where along it the match lies.
// 2. The inverse depths [1/max_depth, 1/min_depth] map to a segment of the
//    epipolar line in the other image, x(rho) = K_o pi(R f + rho t) with
//    T_o_h = [R, t] and f the pixel's bearing. The segment is searched in
//    steps of 1 px with a 5 x 3 pattern laid along the line in the host
//    image (mapped into the other image by the local affine warp at the
//    middle depth), scored by zero-mean normalised cross-correlation (the two
//    cameras expose differently).
// 3. The best match must reach min_ncc, be unique (uniqueness_ratio) and not
//    sit at an end of the segment; a parabola through the scores gives the
//    sub-pixel position s, and rho follows in closed form from the line.
// 4. Its variance is the disparity error through d rho / d s (sigma_I and
//    sigma_l are given at level 0; a level averages 4^level pixels, so there
//    both are divided by 2^level):
//      V = (d rho / d s)^2 (sigma_photo^2 + sigma_geo^2)
//      sigma_photo^2 = 2 sigma_I^2 / sum_k (g_o,k . l)^2   intensity noise in
//                                                     both images, g_o,k the
//                                                     other image's gradient at
//                                                     pattern sample k, l the
//                                                     line direction
//      sigma_geo^2 = sigma_l^2 (g . n)^2 / (g . e)^2  an epipolar line off by
//                                                     sigma_l moves the match
//                                                     of an edge with gradient
//                                                     g along the line (e its
//                                                     host direction, n normal)
//    (LSD-SLAM's photometric and geometric disparity errors, eqs. 5-8, with
//    the photometric one summed over the pattern as for any least-squares
//    alignment of several samples.)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "frontend/direct_options.h"
#include "frontend/image_pyramid.h"

namespace vio {

// A host pixel with its inverse depth.
struct DepthPoint {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // pixel at its level [px]
  double intensity = 0.0;  // the host image's value there [grey]
  double rho = 0.0;        // inverse depth in the host camera [1/m]
  double variance = 0.0;   // variance of rho [1/m^2]
};

// What one StereoInverseDepth call did with the pixels of the host level.
struct StereoDepthStats {
  int candidates = 0;   // pixels with |grad I| >= min_gradient
  int along_edge = 0;   // gradient too perpendicular to the line
  int out_of_view = 0;  // the search segment leaves the other image
  int low_ncc = 0;      // best score below min_ncc
  int ambiguous = 0;    // not unique, or at an end of the segment
  int accepted = 0;     // points returned
};

// Inverse depths of the pixels of `host` (the left image at pyramid level
// `level`) matched into `other` (the right image at the same level).
// T_o_h maps host-camera points into the other camera (T_c1_c0 for EuRoC's
// pair). Throws std::invalid_argument when the options do not validate.
std::vector<DepthPoint> StereoInverseDepth(const PyramidLevel& host,
                                           const PyramidLevel& other,
                                           const Eigen::Isometry3d& T_o_h,
                                           int level,
                                           const StereoDepthOptions& options,
                                           StereoDepthStats* stats = nullptr);

}  // namespace vio

#endif  // VIO_FRONTEND_STEREO_DEPTH_H_
