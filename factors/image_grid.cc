#include "factors/image_grid.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace vio {
namespace {

std::vector<float> Checked(int width, int height, std::vector<float> values) {
  if (width < 4 || height < 4) {
    throw std::invalid_argument(
        "ImageGrid: the image must be at least 4 x 4 (got " +
        std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  const size_t expected =
      static_cast<size_t>(width) * static_cast<size_t>(height);
  if (values.size() != expected) {
    throw std::invalid_argument(
        "ImageGrid: expected " + std::to_string(expected) + " values for " +
        std::to_string(width) + " x " + std::to_string(height) + " (got " +
        std::to_string(values.size()) + ")");
  }
  return values;
}

}  // namespace

ImageGrid::ImageGrid(int width, int height, std::vector<float> values)
    : width_(width),
      height_(height),
      values_(Checked(width, height, std::move(values))),
      grid_(values_.data(), 0, height_, 0, width_),
      interpolator_(grid_) {}

double ImageGrid::Value(double u, double v) const {
  double value = 0.0;
  interpolator_.Evaluate(v, u, &value, nullptr, nullptr);
  return value;
}

void ImageGrid::Evaluate(double u, double v, double* value, double* d_du,
                         double* d_dv) const {
  // Ceres indexes (row, column) = (v, u).
  interpolator_.Evaluate(v, u, value, d_dv, d_du);
}

bool ImageGrid::Inside(double u, double v, double margin) const {
  return std::isfinite(u) && std::isfinite(v) && u >= margin && v >= margin &&
         u <= width_ - 1 - margin && v <= height_ - 1 - margin;
}

}  // namespace vio
