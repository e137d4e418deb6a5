#include "tools/vio_replay_images.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <opencv2/core/utility.hpp>
#include <string>

namespace vio {

bool UsesImages(const EurocSequence& seq, int cameras_used) {
  for (int c = 0; c < cameras_used; ++c) {
    const EurocCamera& camera = seq.data.cameras[c];
    if (camera.has_features || !camera.has_images) return false;
  }
  return true;
}

ImageReplay ReplayImages(const EurocSequence& seq,
                         const FrontendOptions& frontend,
                         const PipelineOptions& pipeline, bool keep_tracks,
                         const ImuSource& imu, Estimator* estimator,
                         LandmarkStream* landmarks,
                         ImageTrackingSummary* summary,
                         ObservationBuilderSummary* removed) {
  // Pipelined, the stages are the parallelism: OpenCV's own pool (TBB here)
  // splitting each LK call over more threads only oversubscribes the cores.
  // One thread runs OpenCV's calls in the caller, with the same results (its
  // parallel loops split independent points and rows).
  if (!pipeline.sequential) cv::setNumThreads(1);
  EurocImageStream stream(seq, frontend, true, !pipeline.sequential);
  StreamingRunner runner(estimator, imu);
  const EurocCamera& cam0 = seq.data.cameras[0];
  Progress progress(static_cast<size_t>(cam0.image_count), cam0.first_image_ns);
  ImageReplay replay;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  RunFramePipeline([&](FeatureFrame* frame) { return stream.Next(frame); },
                   [&](FeatureFrame&& frame) {
                     replay.outputs.push_back(runner.AddFrame(frame));
                     landmarks->Take(estimator);
                     progress.Update(replay.outputs.size() - 1, frame.t_ns);
                     if (keep_tracks) replay.frames.push_back(std::move(frame));
                   },
                   pipeline);
  replay.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  replay.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  progress.Finish();
  *summary = stream.summary();
  *removed = stream.builder_summary();
  return replay;
}


std::string DescribeImageReplay(const ImageTrackingSummary& summary,
                                int cameras_used, double wall_s, double cpu_s,
                                bool sequential) {
  const double n = static_cast<double>(summary.frames);
  std::string text = DescribeImageTracking(summary, cameras_used);
  char line[256];
  // Pipelined, the process CPU clock also counts the estimator's thread
  // while the frontend runs: the frontend's CPU figure is sequential's.
  if (sequential) {
    std::snprintf(line, sizeof(line), "  frontend    %.2f ms/frame CPU, ",
                  n > 0 ? 1e3 * summary.track_cpu_seconds / n : 0.0);
  } else {
    std::snprintf(line, sizeof(line), "  frontend    ");
  }
  text += line;
  std::snprintf(
      line, sizeof(line),
      "%.2f ms wall (%.1f frames/s); image decoding %.2f ms/frame\n",
      n > 0 ? 1e3 * summary.track_seconds / n : 0.0,
      summary.track_seconds > 0 ? n / summary.track_seconds : 0.0,
      n > 0 ? 1e3 * summary.read_seconds / n : 0.0);
  text += line;
  std::snprintf(line, sizeof(line),
                "  full replay %.1f frames/s wall, %.2f ms/frame process CPU "
                "(images, frontend and estimator, %s)\n",
                wall_s > 0 ? n / wall_s : 0.0, n > 0 ? 1e3 * cpu_s / n : 0.0,
                sequential ? "sequential" : "pipelined");
  text += line;
  return text;
}

}  // namespace vio
