#include "frontend/image_pyramid.h"

#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

std::shared_ptr<const ImageGrid> ToGrid(const cv::Mat& image) {
  const cv::Mat continuous = image.isContinuous() ? image : image.clone();
  const float* data = continuous.ptr<float>();
  return std::make_shared<const ImageGrid>(
      continuous.cols, continuous.rows,
      std::vector<float>(data, data + continuous.total()));
}

}  // namespace

ImagePyramid::ImagePyramid(const cv::Mat& image, const Pinhole& camera,
                           int num_levels) {
  if (image.empty() || image.channels() != 1 ||
      (image.depth() != CV_32F && image.depth() != CV_8U)) {
    throw std::invalid_argument(
        "ImagePyramid: expected a single-channel 8-bit or float image");
  }
  if (num_levels < 1) {
    throw std::invalid_argument("ImagePyramid: num_levels must be >= 1 (got " +
                                std::to_string(num_levels) + ")");
  }
  cv::Mat current;
  image.convertTo(current, CV_32F);
  Pinhole K = camera;
  for (int l = 0; l < num_levels; ++l) {
    if (current.cols < 8 || current.rows < 8) {
      throw std::invalid_argument("ImagePyramid: level " + std::to_string(l) +
                                  " would be " + std::to_string(current.cols) +
                                  "x" + std::to_string(current.rows) +
                                  " px (fewer levels, or a larger image)");
    }
    levels_.push_back({ToGrid(current), K});
    if (l + 1 == num_levels) break;
    // Exact 2 x 2 block means over the even part of the image.
    const cv::Mat even =
        current(cv::Rect(0, 0, current.cols / 2 * 2, current.rows / 2 * 2));
    cv::Mat half;
    cv::resize(even, half, cv::Size(even.cols / 2, even.rows / 2), 0, 0,
               cv::INTER_AREA);
    current = half;
    K = K.Halved();
  }
}

}  // namespace vio
