#include "tools/image_tracks.h"

#include <chrono>
#include <ctime>
#include <exception>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "dataset/features_csv.h"
#include "frontend/image_frontend.h"
#include "tools/bounded_queue.h"

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

// A camera's image list, to be read as the frames need it.
std::unique_ptr<ImageListStream> OpenList(const EurocCamera& camera) {
  return std::make_unique<ImageListStream>(JoinPath(camera.folder, "data.csv"),
                                           JoinPath(camera.folder, "data"));
}

}  // namespace

int64_t ImageTrackingSummary::skipped() const {
  int64_t n = 0;
  for (const ImageCounts& c : cameras) {
    n += c.missing + c.unreadable + c.wrong_size;
  }
  return n;
}

// One frame between the steps. `counts` and `read_seconds` are what reading
// it (and the bad images skipped before it) added; an `end` item carries
// only the counts of the sequence's last images.
struct EurocImageStream::Work {
  bool end = false;
  int64_t t_ns = 0;
  cv::Mat left;
  StereoImage right;
  TrackedFrame tracked;
  ImageCounts counts[2];
  double read_seconds = 0.0;
  double track_seconds = 0.0;
  double track_cpu_seconds = 0.0;
};

// The buffers of the prepared right images (two LK pyramids with their
// derivatives, about 2.6 MB a frame) go back from Finish to Read, so they
// are allocated once instead of mapped and faulted in for every frame.
struct EurocImageStream::Spares {
  std::mutex mutex;
  std::vector<StereoImage> images;

  StereoImage Take() {
    std::lock_guard<std::mutex> lock(mutex);
    if (images.empty()) return StereoImage();
    StereoImage image = std::move(images.back());
    images.pop_back();
    return image;
  }
  void Give(StereoImage&& image) {
    std::lock_guard<std::mutex> lock(mutex);
    images.push_back(std::move(image));
  }
};

struct EurocImageStream::Threads {
  BoundedQueue<Work> read{kStageQueueFrames};
  BoundedQueue<Work> tracked{kStageQueueFrames};
  std::exception_ptr read_error, track_error;
  std::thread reader, tracker;
};

EurocImageStream::EurocImageStream(const EurocSequence& sequence,
                                   const FrontendOptions& options,
                                   bool with_observations, bool threaded)
    : sequence_(sequence),
      spares_(std::make_unique<Spares>()),
      threaded_(threaded) {
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
  left_list_ = OpenList(cameras[0]);
  if (options.stereo) right_list_ = OpenList(cameras[1]);
}

EurocImageStream::~EurocImageStream() {
  if (!threads_) return;
  // Unblocks both threads wherever they wait; they stop at their next push.
  threads_->read.Close();
  threads_->tracked.Close();
  threads_->read.Clear();
  threads_->tracked.Clear();
  threads_->reader.join();
  threads_->tracker.join();
}

const ObservationBuilderSummary& EurocImageStream::builder_summary() const {
  static const ObservationBuilderSummary kNone;
  return builder_ ? builder_->summary() : kNone;
}

std::optional<ImageEntry> EurocImageStream::RightAt(int64_t t_ns,
                                                    int64_t* unpaired) {
  for (;;) {
    if (!right_next_) {
      ImageEntry entry;
      if (!right_list_->Next(&entry)) return std::nullopt;
      right_next_ = std::move(entry);
    }
    if (right_next_->t_ns > t_ns) return std::nullopt;
    if (right_next_->t_ns == t_ns) {
      ImageEntry match = std::move(*right_next_);
      right_next_.reset();
      return match;
    }
    right_next_.reset();
    ++*unpaired;
  }
}

void EurocImageStream::FinishLists(ImageCounts counts[2]) {
  counts[0].missing += left_list_->missing();
  if (!right_list_) return;
  if (right_next_) ++counts[1].unpaired;
  right_next_.reset();
  ImageEntry entry;
  while (right_list_->Next(&entry)) ++counts[1].unpaired;
  counts[1].missing += right_list_->missing();
}

bool EurocImageStream::Read(Work* work) {
  ImageEntry entry;
  while (left_list_->Next(&entry)) {
    std::optional<ImageEntry> right_entry;
    if (right_list_) {
      right_entry = RightAt(entry.t_ns, &work->counts[1].unpaired);
    }
    const Clock::time_point start = Clock::now();
    cv::Mat left =
        ReadImage(entry.path, sequence_.cameras[0], &work->counts[0]);
    cv::Mat right;
    if (right_entry) {
      if (!left.empty()) {
        right = ReadImage(right_entry->path, sequence_.cameras[1],
                          &work->counts[1]);
      } else {
        ++work->counts[1].unpaired;
      }
    }
    work->read_seconds += SecondsSince(start);
    if (left.empty()) continue;
    work->t_ns = entry.t_ns;
    work->left = std::move(left);
    // Preparing the right image is the frontend's work: timed as tracking.
    const Clock::time_point prepare = Clock::now();
    const std::clock_t cpu_start = std::clock();
    work->right = spares_->Take();
    frontend_->PrepareRight(right, &work->right);
    work->track_cpu_seconds +=
        static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    work->track_seconds += SecondsSince(prepare);
    return true;
  }
  FinishLists(work->counts);
  work->end = true;
  return false;
}

void EurocImageStream::Track(Work* work) {
  const Clock::time_point start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  work->tracked = frontend_->TrackLeft(work->t_ns, work->left);
  work->left.release();
  work->track_cpu_seconds +=
      static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  work->track_seconds += SecondsSince(start);
}

void EurocImageStream::AddCounts(const Work& work) {
  for (int c = 0; c < 2; ++c) {
    ImageCounts& n = summary_.cameras[c];
    n.used += work.counts[c].used;
    n.missing += work.counts[c].missing;
    n.unreadable += work.counts[c].unreadable;
    n.wrong_size += work.counts[c].wrong_size;
    n.unpaired += work.counts[c].unpaired;
  }
  summary_.read_seconds += work.read_seconds;
  summary_.track_seconds += work.track_seconds;
  summary_.track_cpu_seconds += work.track_cpu_seconds;
}

void EurocImageStream::Finish(Work* work, FeatureFrame* frame) {
  const Clock::time_point start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  frontend_->MatchRight(work->right, &work->tracked);
  spares_->Give(std::move(work->right));
  work->track_cpu_seconds +=
      static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  work->track_seconds += SecondsSince(start);
  AddCounts(*work);
  *frame = std::move(work->tracked.frame);
  ++summary_.frames;
  if (work->tracked.stats.stereo_matched) ++summary_.stereo_frames;
  for (const FeatureObservation& o : frame->observations) {
    ++summary_.observations[o.camera == 0 ? 0 : 1];
  }
  if (builder_) builder_->Process(frame);
}

void EurocImageStream::StartThreads() {
  threads_ = std::make_unique<Threads>();
  Threads* t = threads_.get();
  t->reader = std::thread([this, t] {
    try {
      for (;;) {
        Work work;
        const bool more = Read(&work);
        if (!t->read.Push(std::move(work)) || !more) break;
      }
    } catch (...) {
      t->read_error = std::current_exception();
    }
    t->read.Close();
  });
  t->tracker = std::thread([this, t] {
    try {
      while (std::optional<Work> work = t->read.Pop()) {
        if (!work->end) Track(&*work);
        if (!t->tracked.Push(std::move(*work))) break;
      }
    } catch (...) {
      t->track_error = std::current_exception();
    }
    // Also unblocks the reader when tracking failed.
    t->read.Close();
    t->tracked.Close();
  });
}

bool EurocImageStream::Next(FeatureFrame* frame) {
  if (finished_) return false;
  Work work;
  if (!threaded_) {
    if (!Read(&work)) {
      AddCounts(work);
      finished_ = true;
      return false;
    }
    Track(&work);
  } else {
    if (!threads_) StartThreads();
    std::optional<Work> next = threads_->tracked.Pop();
    if (!next) {
      // Closed without an end: a step failed. The later step's error first:
      // it happened on an earlier frame.
      finished_ = true;
      if (threads_->track_error) std::rethrow_exception(threads_->track_error);
      if (threads_->read_error) std::rethrow_exception(threads_->read_error);
      return false;
    }
    work = std::move(*next);
    if (work.end) {
      AddCounts(work);
      finished_ = true;
      return false;
    }
  }
  Finish(&work, frame);
  return true;
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
