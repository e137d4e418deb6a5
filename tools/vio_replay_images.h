#ifndef VIO_TOOLS_VIO_REPLAY_IMAGES_H_
#define VIO_TOOLS_VIO_REPLAY_IMAGES_H_

// vio_replay on a sequence of images: the frontend tracks them while the
// estimator runs, frame by frame, and the summary gives the frontend's and
// the whole replay's speed.

#include <string>
#include <vector>

#include "config/euroc_sequence.h"
#include "estimator/estimator.h"
#include "frontend/observation_builder.h"
#include "tools/frame_pipeline.h"
#include "tools/image_tracks.h"
#include "tools/vio_replay_report.h"

namespace vio {

// True when every used camera has images and none has features.csv: the
// frontend tracks them.
bool UsesImages(const EurocSequence& seq, int cameras_used);

// What an image replay produced: one output per frame; the frames with
// their observations only when kept (--save-tracks), so that memory does
// not grow with the sequence beyond the outputs.
struct ImageReplay {
  std::vector<EstimatorOutput> outputs;
  std::vector<FeatureFrame> frames;  // empty without --save-tracks
  double wall_s = 0.0;               // images, frontend and estimator [s]
  double cpu_s = 0.0;                // process CPU over the same span [s]
};

// Reads, tracks and estimates the images frame by frame: reading, cam0
// tracking and the stereo match on three threads ahead of the estimator
// (EurocImageStream threaded, RunFramePipeline), or all on this one
// (pipeline.sequential).
// The estimator gets the same frames in the same order either way.
// After each frame the finished landmarks go to `landmarks`.
ImageReplay ReplayImages(const EurocSequence& seq,
                         const FrontendOptions& frontend,
                         const PipelineOptions& pipeline, bool keep_tracks,
                         const ImuSource& imu, Estimator* estimator,
                         LandmarkStream* landmarks,
                         ImageTrackingSummary* summary,
                         ObservationBuilderSummary* removed);

// The summary's image lines: the tracking counts (DescribeImageTracking),
// the frontend's time per frame and the whole replay's frames per second
// and process CPU (wall_s, cpu_s: ImageReplay's).
std::string DescribeImageReplay(const ImageTrackingSummary& summary,
                                int cameras_used, double wall_s, double cpu_s,
                                bool sequential);

}  // namespace vio

#endif  // VIO_TOOLS_VIO_REPLAY_IMAGES_H_
