#include "render/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vio {

SensorModel::SensorModel(const CameraCalibration& c,
                         const RenderOptions& options)
    : read_noise_grey_(options.read_noise_grey),
      shot_noise_grey_(options.shot_noise_grey) {
  double r2_corner = 0.0;
  for (double u : {0.0, c.width - 1.0}) {
    for (double v : {0.0, c.height - 1.0}) {
      r2_corner = std::max(r2_corner,
                           (u - c.cx) * (u - c.cx) + (v - c.cy) * (v - c.cy));
    }
  }
  const double falloff = (1.0 - options.vignetting_corner_gain) / r2_corner;
  vignetting_.create(c.height, c.width, CV_32F);
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      const double r2 = (u - c.cx) * (u - c.cx) + (v - c.cy) * (v - c.cy);
      vignetting_.at<float>(v, u) =
          static_cast<float>(std::max(0.0, 1.0 - falloff * r2));
    }
  }
}

void SensorModel::Expose(const cv::Mat& radiance, double gain, uint64_t seed,
                         cv::Mat* image) const {
  if (radiance.type() != CV_32F || radiance.size() != vignetting_.size()) {
    throw std::invalid_argument(
        "SensorModel::Expose: the radiance must be 32-bit float of the "
        "calibration's size");
  }
  cv::multiply(radiance, vignetting_, intensity_, gain);
  if (read_noise_grey_ > 0.0 || shot_noise_grey_ > 0.0) {
    // sigma = sqrt(read^2 + shot * max(I, 0)), per pixel.
    cv::max(intensity_, 0.0, sigma_);
    sigma_.convertTo(sigma_, CV_32F, shot_noise_grey_,
                     read_noise_grey_ * read_noise_grey_);
    cv::sqrt(sigma_, sigma_);
    noise_.create(intensity_.size(), CV_32F);
    cv::RNG rng(seed);
    rng.fill(noise_, cv::RNG::NORMAL, 0.0, 1.0);
    cv::multiply(noise_, sigma_, noise_);
    intensity_ += noise_;
  }
  intensity_.convertTo(*image, CV_8U);  // rounds and saturates
}

}  // namespace vio
