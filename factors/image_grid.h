#ifndef VIO_FACTORS_IMAGE_GRID_H_
#define VIO_FACTORS_IMAGE_GRID_H_

// A grey image as the photometric factor sees it: a plain row-major buffer of
// intensities behind ceres::Grid2D, read through ceres::BiCubicInterpolator.
// Bicubic (Catmull-Rom / Keys) interpolation is continuously differentiable,
// so the photometric residual is smooth enough to differentiate numerically
// and its analytic Jacobian can be checked like every other factor's. No
// OpenCV here: whoever decodes images hands in the values.
//
// Pixel convention (OpenCV's): u is the column (right), v the row (down), and
// the centre of the top-left pixel is (0, 0). Grid2D extends the image by its
// edge values; Inside() says where the 4 x 4 interpolation support lies
// wholly inside the image, which is where a residual may use the image.

#include <ceres/cubic_interpolation.h>

#include <memory>
#include <vector>

namespace vio {

class ImageGrid {
 public:
  // `values` holds width * height intensities, row by row. Throws
  // std::invalid_argument for sizes below 4 x 4 or a buffer of the wrong
  // length.
  ImageGrid(int width, int height, std::vector<float> values);

  // The interpolator refers to the grid, which refers to the buffer: the
  // object cannot be copied or moved. Share it (std::shared_ptr).
  ImageGrid(const ImageGrid&) = delete;
  ImageGrid& operator=(const ImageGrid&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  // The stored value of pixel (u, v), integers inside the image.
  float At(int u, int v) const { return values_[v * width_ + u]; }
  const std::vector<float>& values() const { return values_; }

  // Interpolated intensity at (u, v), and optionally its gradient
  // d/du, d/dv [grey/px]. Call only where Inside(u, v, 1) holds (else the
  // edge extension is used, and far outside the integer conversion of
  // floor(u) would overflow).
  double Value(double u, double v) const;
  void Evaluate(double u, double v, double* value, double* d_du,
                double* d_dv) const;

  // True when (u, v) is finite and at least `margin` px inside the image:
  // margin <= u <= width - 1 - margin, same for v. With margin >= 2 the
  // bicubic support (floor(u) - 1 .. floor(u) + 2) lies inside the image, so
  // values and gradients are the image's own.
  bool Inside(double u, double v, double margin) const;

 private:
  int width_, height_;
  std::vector<float> values_;
  ceres::Grid2D<float, 1> grid_;
  ceres::BiCubicInterpolator<ceres::Grid2D<float, 1>> interpolator_;
};

// The margin [px] inside which the bicubic support stays in the image.
constexpr double kImageGridMargin = 2.0;

}  // namespace vio

#endif  // VIO_FACTORS_IMAGE_GRID_H_
