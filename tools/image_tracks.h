#ifndef VIO_TOOLS_IMAGE_TRACKS_H_
#define VIO_TOOLS_IMAGE_TRACKS_H_

// Images of an EuRoC-layout sequence -> feature frames, for the tools that
// replay recorded images (vio_track, vio_replay). This is where image files
// are read: the frontend itself only sees cv::Mat. A bad image never stops
// the run: it is skipped and counted, and the summary says how many.
//
// Frames follow cam0: each cam0 image is one frame; in stereo, the cam1
// image with the same stamp is matched into it. A frame whose cam0 image is
// bad is dropped; a frame whose cam1 image is bad or absent is tracked on
// cam0 alone.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/euroc_sequence.h"
#include "dataset/euroc_csv_stream.h"
#include "frontend/frontend_options.h"
#include "frontend/observation_builder.h"
#include "geometry/feature_observation.h"

namespace vio {

class ImageFrontend;  // frontend/image_frontend.h

// Counts for one camera.
struct ImageCounts {
  int64_t used = 0;        // images that reached the frontend
  int64_t missing = 0;     // listed in data.csv, absent on disk: skipped
  int64_t unreadable = 0;  // present but not decodable: skipped
  int64_t wrong_size = 0;  // not the sensor.yaml resolution: skipped
  int64_t unpaired = 0;    // cam1 only: no cam0 image at its stamp: unused
};

struct ImageTrackingSummary {
  ImageCounts cameras[2];          // cam0, cam1
  int64_t frames = 0;              // frames emitted (one per good cam0 image)
  int64_t stereo_frames = 0;       // of which matched into cam1
  int64_t observations[2] = {};    // emitted per camera
  double read_seconds = 0.0;       // wall time decoding images [s]
  double track_seconds = 0.0;      // wall time in the frontend [s]
  double track_cpu_seconds = 0.0;  // process CPU time in the frontend [s]

  int64_t skipped() const;  // missing + unreadable + wrong size, both cameras
};

// The sequence's images tracked one frame at a time, read as they are asked
// for (vio_replay's pipeline): the same frames, in the same order, as
// TrackEurocImages / ImageObservations. Throws std::invalid_argument on
// construction as TrackEurocImages does.
//
// The image lists (camN/data.csv) are read here too, a line at a time as
// the frames need them (ImageListStream, dataset/euroc_csv_stream.h), not
// taken from sequence.data.cameras[c].images, which may be empty
// (EurocReadOptions::keep_image_lists): memory does not grow with the
// sequence's length. cam1's list is walked alongside cam0's by stamp (both
// strictly increase); its images without a cam0 partner are counted as
// unpaired as they are passed, those after cam0's last at the end. A line
// the loader accepted cannot fail here unless the file changed since; then
// the DatasetError is the stream's error (see below).
//
// Each frame goes through three steps: read (decode both images, prepare
// the right one for the stereo match), track (cam0, whose state carries from
// frame to frame) and finish (the stereo match, the observation step). With
// `threaded`, reading and tracking each run on their own thread, up to
// kStageQueueFrames frames ahead of the next, and Next only finishes: every
// step still sees the frames in order and computes the same values, so the
// frames are bit for bit those of one thread. An exception in a step ends
// the stream after the frames before it and is rethrown by Next.
class EurocImageStream {
 public:
  // with_observations: also the observation step (ImageObservations);
  // otherwise the frames of TrackEurocImages. `sequence` must outlive this.
  EurocImageStream(const EurocSequence& sequence,
                   const FrontendOptions& options, bool with_observations,
                   bool threaded = false);
  ~EurocImageStream();

  // Reads and tracks the next good cam0 image into *frame; false at the end.
  bool Next(FeatureFrame* frame);

  // How far reading may run ahead of tracking, and tracking ahead of Next,
  // when threaded [frames].
  static constexpr size_t kStageQueueFrames = 2;

  const ImageTrackingSummary& summary() const { return summary_; }
  const ObservationBuilderSummary& builder_summary() const;

 private:
  const EurocSequence& sequence_;
  ImageTrackingSummary summary_;
  std::unique_ptr<CameraModel> cam0_;
  std::unique_ptr<CameraModel> cam1_;
  std::unique_ptr<ImageFrontend> frontend_;
  std::unique_ptr<ObservationBuilder> builder_;  // null: no observation step
  std::unique_ptr<ImageListStream> left_list_;
  std::unique_ptr<ImageListStream> right_list_;  // null in mono
  // cam1's next image, not yet passed by cam0's stamps.
  std::optional<ImageEntry> right_next_;
  bool finished_ = false;

  struct Work;     // one frame between the steps
  struct Threads;  // the reading and tracking threads and their queues
  struct Spares;   // prepared right images' buffers, from Finish to Read
  std::unique_ptr<Spares> spares_;
  // The steps (see the class comment). Read returns false at the end, with
  // the last counts in *work.
  bool Read(Work* work);
  void Track(Work* work);
  void Finish(Work* work, FeatureFrame* frame);
  void AddCounts(const Work& work);
  // The cam1 image at `t_ns` (cam0's next stamp), if listed; the cam1 images
  // before it are counted in *unpaired.
  std::optional<ImageEntry> RightAt(int64_t t_ns, int64_t* unpaired);
  // After cam0's last image: cam1's remaining images counted in *unpaired,
  // both lists' missing images in counts.
  void FinishLists(ImageCounts counts[2]);
  void StartThreads();
  const bool threaded_;
  std::unique_ptr<Threads> threads_;
};

// Tracks the sequence's images (cam0, and cam1 when options.stereo). The
// frames carry feature_id, camera and uv; xy and velocity are left to
// frontend/observation_builder. Throws std::invalid_argument when the
// sequence has no cam0 images, or (in stereo) no cam1 images.
std::vector<FeatureFrame> TrackEurocImages(const EurocSequence& sequence,
                                           const FrontendOptions& options,
                                           ImageTrackingSummary* summary);

// TrackEurocImages, then the observation step every feature takes before the
// estimator (frontend/observation_builder: undistorted xy, image velocity),
// with the sequence's camera models. `builder` (optional) receives what that
// step removed.
std::vector<FeatureFrame> ImageObservations(
    const EurocSequence& sequence, const FrontendOptions& options,
    ImageTrackingSummary* summary,
    ObservationBuilderSummary* builder = nullptr);

// A few lines for a tool's summary: frames, observations and, per camera,
// the images used and skipped (by reason).
std::string DescribeImageTracking(const ImageTrackingSummary& summary,
                                  int num_cameras);

// Where --save-tracks FILE puts camera `camera`'s observations: cam0 in FILE
// itself, camera N > 0 in FILE with ".camN" inserted before the extension
// ("tracks.csv" -> "tracks.cam1.csv").
std::string TracksPathForCamera(const std::string& path, int camera);

// Writes every camera's observations of `frames` in the features.csv format
// (dataset/features_csv.h), one file per camera (TracksPathForCamera).
// Returns the files written. Throws DatasetError when one cannot be written.
std::vector<std::string> SaveTracks(const std::string& path,
                                    const std::vector<FeatureFrame>& frames,
                                    int num_cameras);

}  // namespace vio

#endif  // VIO_TOOLS_IMAGE_TRACKS_H_
