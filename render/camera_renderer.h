#ifndef VIO_RENDER_CAMERA_RENDERER_H_
#define VIO_RENDER_CAMERA_RENDERER_H_

// Renders what one calibrated camera sees of a textured scene, by per-plane
// perspective warps (cv::warpPerspective) and one distortion remap
// (cv::remap), never by per-pixel ray casting:
//
//   1. An undistorted pinhole image ("the pinhole view") with the camera's
//      focal lengths times view_scale, large enough that every pixel of the
//      distorted image maps into it. Each plane seen from its front is clipped
//      to the near plane and to the view; the texture-to-view homography
//        H = K [R_c_w u / rho | R_c_w v / rho | R_c_w X(0.5/rho, 0.5/rho) +
//        t_c_w]
//      (texture layout of render/texture_atlas.h) warps its texture into the
//      plane's polygon. Where the polygon overlaps another, the nearer one
//      wins by a z-buffer of inverse depth, which is affine in the pixel:
//      the third row of G = H^-1 applied to (u, v, 1) is 1/z.
//   2. Mip level per pixel, without per-pixel work: the warp's texels per
//      pixel m = sqrt(|det G| / w^3), w = 1/z, depend on w alone, so the
//      pixels of one level form a band between two lines of constant w.
//      The polygon is cut into those bands and each band warps its own
//      level (level = log2 m + mip_bias, rounded).
//   3. The distorted image: cv::remap of the pinhole view through the
//      camera model's undistortion of every pixel (maps made once).
//
// Pixel convention: OpenCV's, the centre of the top-left pixel at (0, 0),
// as the camera model and the frontend use.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "geometry/camera_model.h"
#include "render/polygon.h"
#include "render/texture_atlas.h"

namespace vio {

// The intermediate undistorted image.
struct PinholeView {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  // [px]
  int width = 0, height = 0;                      // [px]
};

class CameraRenderer {
 public:
  // `scene` must outlive the renderer. Throws std::invalid_argument when
  // a pixel of the calibration's image cannot be undistorted or lies beyond
  // 80 degrees from the optical axis (no pinhole view can hold it).
  // view_scale in (0, 4] scales the view's focal lengths (1: as sharp as
  // the camera at the image centre).
  CameraRenderer(const CameraCalibration& calibration,
                 const TexturedScene* scene, double view_scale = 1.0,
                 double mip_bias = 0.0);

  // The pinhole view of the scene from camera pose T_w_c (8-bit; 0 where no
  // plane is seen) and, optionally, the inverse depth of every pixel (32-bit
  // float [1/m], 0 where no plane is seen).
  void RenderPinhole(const Eigen::Isometry3d& T_w_c, cv::Mat* image,
                     cv::Mat* inverse_depth = nullptr) const;

  // The camera's distorted image (32-bit float grey levels, calibration
  // size): the mean of the renders at the poses T_w_c (several poses over
  // an exposure give motion blur). `radiance` is reused when it already has
  // that size and type. Throws std::invalid_argument when `T_w_c` is empty.
  void RenderRadiance(const std::vector<Eigen::Isometry3d>& T_w_c,
                      cv::Mat* radiance) const;

  // The inverse depth [1/m] of every pixel of the distorted image (nearest
  // pinhole pixel; 0 where no plane is seen).
  cv::Mat RenderInverseDepth(const Eigen::Isometry3d& T_w_c) const;

  const PinholeView& pinhole() const { return pinhole_; }
  const CameraModel& camera() const { return camera_; }

 private:
  // One plane's texture-to-view warp at one mip level.
  struct PlaneWarp {
    Eigen::Matrix3d H;   // level-0 texel -> view pixel
    Eigen::Vector3d g2;  // third row of H^-1: 1/z = g2 . (u, v, 1)
    const cv::Mat* texture = nullptr;  // the level's texture
    double scale = 1.0;                // 2^level
  };

  // Draws plane `index` into the view, with a depth test against (and an
  // update of) the inverse-depth buffer when `depth_test`; `inverse_depth`
  // (optional) is the buffer and is always updated.
  void DrawPlane(size_t index, const Eigen::Isometry3d& T_c_w, cv::Mat* image,
                 cv::Mat* inverse_depth, bool depth_test) const;
  // Warps `warp` into the convex view polygon `poly`, cut in two (up to
  // six times deep) while it fills little of its bounding rectangle.
  void DrawPolygon(const Polygon& poly, const PlaneWarp& warp, cv::Mat* image,
                   cv::Mat* inverse_depth, bool depth_test, int depth) const;

  CameraModel camera_;
  const TexturedScene* scene_;
  double mip_bias_;
  PinholeView pinhole_;
  cv::Mat map_fixed_, map_fraction_;  // distortion remap (cv::convertMaps)
  cv::Mat map_x_, map_y_;             // the same as float maps
  cv::Mat ramp_u_, ramp_v_;           // pixel coordinates of the view
  // Buffers reused from frame to frame: a fresh image-sized allocation is
  // a fresh mmap whose page faults can cost more than the render itself.
  // (So a renderer is not thread-safe: one per thread.)
  struct Scratch {
    cv::Mat warped, mask, nearer, w;  // view-sized, per-polygon ROIs
    cv::Mat depth;                    // inverse depth when none is asked
    cv::Mat view, sum, distorted;
  };
  mutable Scratch scratch_;
};

}  // namespace vio

#endif  // VIO_RENDER_CAMERA_RENDERER_H_
