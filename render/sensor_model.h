#ifndef VIO_RENDER_SENSOR_MODEL_H_
#define VIO_RENDER_SENSOR_MODEL_H_

// What the image sensor makes of the rendered radiance: exposure gain,
// vignetting, noise and 8-bit quantisation,
//
//   I  = radiance(u, v) * gain * vignetting(u, v)
//   out = round(clamp(I + n, 0, 255)),  n ~ N(0, read^2 + shot * max(I, 0))
//
// vignetting(u, v) = 1 - (1 - corner_gain) (r / r_corner)^2, r the distance
// of the pixel from the principal point and r_corner that of the farthest
// image corner.

#include <cstdint>
#include <opencv2/core.hpp>

#include "geometry/camera_model.h"
#include "render/render_options.h"

namespace vio {

class SensorModel {
 public:
  SensorModel(const CameraCalibration& calibration,
              const RenderOptions& options);

  // The 8-bit image of a 32-bit float radiance of the calibration's size,
  // into `image` (reused when it has the size and type); the noise is drawn
  // from cv::RNG(seed). Throws std::invalid_argument for a radiance of
  // another size or type. Not thread-safe (scratch buffers).
  void Expose(const cv::Mat& radiance, double gain, uint64_t seed,
              cv::Mat* image) const;

  const cv::Mat& vignetting() const { return vignetting_; }  // 32-bit float

 private:
  cv::Mat vignetting_;
  double read_noise_grey_;
  double shot_noise_grey_;
  mutable cv::Mat intensity_, sigma_, noise_;  // reused from call to call
};

}  // namespace vio

#endif  // VIO_RENDER_SENSOR_MODEL_H_
