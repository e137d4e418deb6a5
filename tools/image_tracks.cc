#include "tools/image_tracks.h"

#include <chrono>
#include <ctime>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "dataset/features_csv.h"
#include "frontend/image_frontend.h"

namespace vio {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Decodes an image as 8-bit grey; an empty Mat (and a count) when it cannot
// be read or is not of the calibration's size.
cv::Mat ReadImage(const std::string& path, const CameraCalibration& camera,
                  ImageCounts* counts) {
  cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    ++counts->unreadable;
    return cv::Mat();
  }
  if (image.cols != camera.width || image.rows != camera.height) {
    ++counts->wrong_size;
    return cv::Mat();
  }
  ++counts->used;
  return image;
}

}  // namespace

int64_t ImageTrackingSummary::skipped() const {
  int64_t n = 0;
  for (const ImageCounts& c : cameras) {
    n += c.missing + c.unreadable + c.wrong_size;
  }
  return n;
}

EurocImageStream::EurocImageStream(const EurocSequence& sequence,
                                   const FrontendOptions& options,
                                   bool with_observations)
    : sequence_(sequence) {
  const std::vector<EurocCamera>& cameras = sequence.data.cameras;
  const int needed = options.stereo ? 2 : 1;
  if (static_cast<int>(cameras.size()) < needed ||
      static_cast<int>(sequence.cameras.size()) < needed) {
    throw std::invalid_argument(
        sequence.data.folder + ": " + (options.stereo ? "stereo" : "mono") +
        " tracking needs cam0" + (options.stereo ? " and cam1" : "") +
        " images");
  }
  for (int c = 0; c < needed; ++c) {
    if (!cameras[c].has_images) {
      throw std::invalid_argument(sequence.data.folder + ": cam" +
                                  std::to_string(c) + " has no data.csv");
    }
  }
  cam0_ = std::make_unique<CameraModel>(sequence.cameras[0]);
  cam1_ = std::make_unique<CameraModel>(sequence.cameras[needed - 1]);
  frontend_ = std::make_unique<ImageFrontend>(
      *cam0_, options.stereo ? cam1_.get() : nullptr, options);
  if (with_observations) {
    std::vector<CameraModel> models;
    for (int c = 0; c < needed; ++c) models.emplace_back(sequence.cameras[c]);
    builder_ = std::make_unique<ObservationBuilder>(models);
  }
  if (options.stereo) {
    summary_.cameras[1].missing = cameras[1].missing_images;
    for (const ImageEntry& e : cameras[1].images) right_by_stamp_[e.t_ns] = &e;
  }
  summary_.cameras[0].missing = cameras[0].missing_images;
}

EurocImageStream::~EurocImageStream() = default;

const ObservationBuilderSummary& EurocImageStream::builder_summary() const {
  static const ObservationBuilderSummary kNone;
  return builder_ ? builder_->summary() : kNone;
}

bool EurocImageStream::Next(FeatureFrame* frame) {
  const std::vector<ImageEntry>& images = sequence_.data.cameras[0].images;
  ImageTrackingSummary* summary = &summary_;
  while (next_ < images.size()) {
    const ImageEntry& entry = images[next_++];
    Clock::time_point start = Clock::now();
    const cv::Mat left =
        ReadImage(entry.path, sequence_.cameras[0], &summary->cameras[0]);
    cv::Mat right;
    auto it = right_by_stamp_.find(entry.t_ns);
    if (it != right_by_stamp_.end()) {
      if (!left.empty()) {
        right = ReadImage(it->second->path, sequence_.cameras[1],
                          &summary->cameras[1]);
      } else {
        ++summary->cameras[1].unpaired;
      }
      right_by_stamp_.erase(it);
    }
    summary->read_seconds += SecondsSince(start);
    if (left.empty()) continue;
    start = Clock::now();
    const std::clock_t cpu_start = std::clock();
    *frame = frontend_->Process(entry.t_ns, left, right);
    summary->track_cpu_seconds +=
        static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    summary->track_seconds += SecondsSince(start);
    ++summary->frames;
    if (frontend_->stats().stereo_matched) ++summary->stereo_frames;
    for (const FeatureObservation& o : frame->observations) {
      ++summary->observations[o.camera == 0 ? 0 : 1];
    }
    if (builder_) builder_->Process(frame);
    if (next_ == images.size()) {
      summary->cameras[1].unpaired +=
          static_cast<int64_t>(right_by_stamp_.size());
      right_by_stamp_.clear();
    }
    return true;
  }
  summary->cameras[1].unpaired += static_cast<int64_t>(right_by_stamp_.size());
  right_by_stamp_.clear();
  return false;
}

std::vector<FeatureFrame> TrackEurocImages(const EurocSequence& sequence,
                                           const FrontendOptions& options,
                                           ImageTrackingSummary* summary) {
  EurocImageStream stream(sequence, options, false);
  std::vector<FeatureFrame> frames;
  FeatureFrame frame;
  while (stream.Next(&frame)) frames.push_back(std::move(frame));
  *summary = stream.summary();
  return frames;
}

std::vector<FeatureFrame> ImageObservations(
    const EurocSequence& sequence, const FrontendOptions& options,
    ImageTrackingSummary* summary, ObservationBuilderSummary* builder) {
  EurocImageStream stream(sequence, options, true);
  std::vector<FeatureFrame> frames;
  FeatureFrame frame;
  while (stream.Next(&frame)) frames.push_back(std::move(frame));
  *summary = stream.summary();
  if (builder) *builder = stream.builder_summary();
  return frames;
}

std::string DescribeImageTracking(const ImageTrackingSummary& summary,
                                  int num_cameras) {
  std::ostringstream out;
  out << "  images      " << summary.frames << " frames ("
      << summary.stereo_frames << " stereo), " << summary.observations[0]
      << " cam0 + " << summary.observations[1] << " cam1 observations, "
      << summary.skipped() << " images skipped\n";
  for (int c = 0; c < num_cameras && c < 2; ++c) {
    const ImageCounts& n = summary.cameras[c];
    out << "    cam" << c << ": " << n.used << " used; skipped: " << n.missing
        << " missing, " << n.unreadable << " unreadable, " << n.wrong_size
        << " wrong size";
    if (c > 0) out << "; " << n.unpaired << " without a cam0 partner";
    out << "\n";
  }
  return out.str();
}

std::string TracksPathForCamera(const std::string& path, int camera) {
  if (camera == 0) return path;
  const size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    dot = path.size();
  }
  return path.substr(0, dot) + ".cam" + std::to_string(camera) +
         path.substr(dot);
}

std::vector<std::string> SaveTracks(const std::string& path,
                                    const std::vector<FeatureFrame>& frames,
                                    int num_cameras) {
  std::vector<std::string> written;
  for (int camera = 0; camera < num_cameras; ++camera) {
    written.push_back(TracksPathForCamera(path, camera));
    WriteFeaturesCsv(written.back(), frames, camera);
  }
  return written;
}

}  // namespace vio
