#ifndef VIO_FRONTEND_IMAGE_PYRAMID_H_
#define VIO_FRONTEND_IMAGE_PYRAMID_H_

// The image pyramid of the direct method: level 0 is the undistorted image,
// each further level averages 2 x 2 blocks of the one below (an odd last row
// or column is dropped), and carries the pinhole that goes with it
// (Pinhole::Halved). Each level is an ImageGrid, which the photometric
// residuals read through Ceres' bicubic interpolator.

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "factors/image_grid.h"
#include "geometry/pinhole.h"

namespace vio {

struct PyramidLevel {
  std::shared_ptr<const ImageGrid> image;
  Pinhole camera;
};

class ImagePyramid {
 public:
  ImagePyramid() = default;
  // `image`: single-channel CV_32F (or CV_8U, converted), the pinhole's
  // image. Throws std::invalid_argument for another type, for fewer than one
  // level, or when a level would be smaller than 8 x 8 px.
  ImagePyramid(const cv::Mat& image, const Pinhole& camera, int num_levels);

  int size() const { return static_cast<int>(levels_.size()); }
  const PyramidLevel& level(int l) const { return levels_.at(l); }

 private:
  std::vector<PyramidLevel> levels_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_IMAGE_PYRAMID_H_
