#include "frontend/corner_detector.h"

#include <algorithm>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

// Shi-Tomasi's covariance window and Sobel aperture (goodFeaturesToTrack's
// defaults, which the tracker used).
constexpr int kBlockSize = 3;
constexpr int kAperture = 3;
// The response is exact on a region shrunk by this much on every side that
// does not touch the image border: the box filter over the covariance reads
// kBlockSize / 2 pixels beyond, which it reflects at the sub-image's edge.
constexpr int kFilterMargin = kBlockSize / 2;
// The local maximum test reads the 8 neighbours of each candidate.
constexpr int kNeighbourMargin = 1;

struct Candidate {
  float response;
  int index;  // y * width + x
};

}  // namespace

CornerDetector::CornerDetector(int tile_px) : tile_px_(tile_px) {
  if (tile_px_ < 1) {
    throw std::invalid_argument("CornerDetector: tile_px must be >= 1 (got " +
                                std::to_string(tile_px_) + ")");
  }
}

std::vector<cv::Point2f> CornerDetector::Detect(const cv::Mat& image,
                                                const cv::Mat& mask,
                                                int max_corners, double quality,
                                                double min_distance) {
  if (image.empty() || image.type() != CV_8UC1 || mask.type() != CV_8UC1 ||
      mask.size() != image.size()) {
    throw std::invalid_argument(
        "CornerDetector::Detect: expected an 8-bit grey image and an 8-bit "
        "mask of its size");
  }
  const int width = image.cols, height = image.rows;
  const cv::Rect whole(0, 0, width, height);
  response_.create(image.size(), CV_32F);
  response_.setTo(0.0f);

  // Runs of neighbouring tiles, in one tile row, that hold an open pixel.
  std::vector<cv::Rect> runs;
  for (int y0 = 0; y0 < height; y0 += tile_px_) {
    const int rows = std::min(tile_px_, height - y0);
    const int columns = (width + tile_px_ - 1) / tile_px_;
    int run_start = -1;
    for (int c = 0; c <= columns; ++c) {  // c == columns closes the last run
      const int x0 = std::min(c * tile_px_, width);
      const bool open = c < columns &&
                        cv::countNonZero(mask(cv::Rect(
                            x0, y0, std::min(tile_px_, width - x0), rows))) > 0;
      if (open && run_start < 0) run_start = x0;
      if (!open && run_start >= 0) {
        runs.emplace_back(run_start, y0, x0 - run_start, rows);
        run_start = -1;
      }
    }
  }

  // The response on each run and its neighbour ring, computed on the run
  // grown by both margins (Sobel reads the image around a sub-image as the
  // whole image's filter would; only the box filter's reflection is wrong,
  // on the outer ring, which is not copied).
  int64_t computed = 0;
  for (const cv::Rect& run : runs) {
    const int grow = kNeighbourMargin + kFilterMargin;
    const cv::Rect region =
        cv::Rect(run.x - grow, run.y - grow, run.width + 2 * grow,
                 run.height + 2 * grow) &
        whole;
    const cv::Rect exact =
        cv::Rect(run.x - kNeighbourMargin, run.y - kNeighbourMargin,
                 run.width + 2 * kNeighbourMargin,
                 run.height + 2 * kNeighbourMargin) &
        whole;
    cv::cornerMinEigenVal(image(region), tile_response_, kBlockSize, kAperture);
    tile_response_(exact - region.tl()).copyTo(response_(exact));
    computed += region.area();
  }
  computed_share_ = std::min(1.0, static_cast<double>(computed) / whole.area());

  double max_response = 0.0;
  cv::minMaxLoc(response_, nullptr, &max_response, nullptr, nullptr, mask);
  const float threshold = static_cast<float>(max_response * quality);

  // Candidates: open pixels off the outer ring, above the threshold, not
  // below any neighbour.
  std::vector<Candidate> candidates;
  for (const cv::Rect& run : runs) {
    const int y_end = std::min(run.y + run.height, height - 1);
    const int x_end = std::min(run.x + run.width, width - 1);
    for (int y = std::max(run.y, 1); y < y_end; ++y) {
      const float* above = response_.ptr<float>(y - 1);
      const float* row = response_.ptr<float>(y);
      const float* below = response_.ptr<float>(y + 1);
      const uchar* open = mask.ptr<uchar>(y);
      for (int x = std::max(run.x, 1); x < x_end; ++x) {
        const float v = row[x];
        if (!open[x] || !(v > threshold) || v <= 0.0f) continue;
        const float neighbours =
            std::max({above[x - 1], above[x], above[x + 1], row[x - 1],
                      row[x + 1], below[x - 1], below[x], below[x + 1]});
        if (v >= neighbours) candidates.push_back({v, y * width + x});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) {
              return a.response != b.response ? a.response > b.response
                                              : a.index > b.index;
            });

  const double min_distance2 = min_distance * min_distance;
  std::vector<cv::Point2f> corners;
  for (const Candidate& c : candidates) {
    if (static_cast<int>(corners.size()) >= max_corners) break;
    const float x = static_cast<float>(c.index % width);
    const float y = static_cast<float>(c.index / width);
    bool far = true;
    for (const cv::Point2f& kept : corners) {
      const double dx = x - kept.x, dy = y - kept.y;
      if (dx * dx + dy * dy < min_distance2) {
        far = false;
        break;
      }
    }
    if (far) corners.emplace_back(x, y);
  }
  return corners;
}

}  // namespace vio
