// The pipelined image replay (tools/frame_pipeline): frames reach the
// consumer in order whatever the queue's size, errors on either side reach
// the caller with their message (no hang, no terminate), and on the real
// V1_01 excerpt (its first 50 frames) the estimator's every output is
// bit-for-bit the same as tracking everything first (today's ImageObservations
// + RunSequence) and as the --sequential mode.

#include "tools/frame_pipeline.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/estimator_config.h"
#include "config/euroc_sequence.h"
#include "config/frontend_config.h"
#include "config/imu_config.h"
#include "config/visual_config.h"
#include "dataset/euroc_csv_stream.h"
#include "estimator/sequence_runner.h"
#include "test/testing/euroc_v1_01.h"
#include "test/testing/temp_folder.h"
#include "tools/image_tracks.h"

namespace vio {
namespace {

// A producer of `count` empty frames stamped 0, 1, 2, ...; throws at frame
// `throw_at` (never when negative).
FrameProducer Counting(int count, int throw_at = -1) {
  auto next = std::make_shared<int>(0);
  return [=](FeatureFrame* frame) {
    if (*next == throw_at) {
      throw std::runtime_error("cam0/data/" + std::to_string(*next) +
                               ".png: cannot be decoded");
    }
    if (*next == count) return false;
    frame->t_ns = (*next)++;
    return true;
  };
}

TEST(FramePipeline, EveryFrameArrivesInOrderWhateverTheQueue) {
  for (const bool sequential : {true, false}) {
    for (const int queue : {1, 2, 8}) {
      PipelineOptions options;
      options.sequential = sequential;
      options.queue_frames = queue;
      std::vector<int64_t> seen;
      RunFramePipeline(
          Counting(200),
          [&](FeatureFrame&& frame) { seen.push_back(frame.t_ns); }, options);
      ASSERT_EQ(seen.size(), 200u);
      for (size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i], static_cast<int64_t>(i));
      }
    }
  }
}

TEST(FramePipeline, ProducerErrorReachesTheCallerWithItsMessage) {
  for (const bool sequential : {true, false}) {
    PipelineOptions options;
    options.sequential = sequential;
    options.queue_frames = 2;
    std::vector<int64_t> seen;
    try {
      RunFramePipeline(
          Counting(100, 37),
          [&](FeatureFrame&& frame) { seen.push_back(frame.t_ns); }, options);
      ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "cam0/data/37.png: cannot be decoded");
    }
    // Every frame made before the error was still estimated.
    EXPECT_EQ(seen.size(), 37u) << (sequential ? "sequential" : "pipelined");
  }
}

TEST(FramePipeline, ConsumerErrorStopsAnEndlessProducer) {
  PipelineOptions options;
  options.queue_frames = 3;
  const FrameProducer endless = [](FeatureFrame* frame) {
    ++frame->t_ns;
    return true;
  };
  int consumed = 0;
  EXPECT_THROW(RunFramePipeline(
                   endless,
                   [&](FeatureFrame&&) {
                     if (++consumed == 5) throw std::logic_error("estimator");
                   },
                   options),
               std::logic_error);
  EXPECT_EQ(consumed, 5);
}

TEST(FramePipeline, RejectsAnEmptyQueue) {
  PipelineOptions options;
  options.queue_frames = 0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  EXPECT_THROW(RunFramePipeline(
                   Counting(3), [](FeatureFrame&&) {}, options),
               std::invalid_argument);
}

// The V1_01 excerpt with its first `frames` cam0 images (a folder of
// links), loaded whole.
EurocSequence ExcerptOf(const testing::TempFolder& dir, int frames) {
  testing::WriteV101Excerpt(dir.path(), frames);
  return LoadEurocSequence(dir.path());
}

// Everything vio_replay builds from config/euroc_stereo.yaml.
struct StereoReplay {
  YamlNode root = YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) +
                                     "/config/euroc_stereo.yaml");
  ImuConfig imu = LoadImuConfig(root);
  EstimatorOptions options;
  FrontendOptions frontend = ReadFrontendOptions(root.Child("frontend"));
  testing::TempFolder dir;
  EurocSequence seq;
  std::vector<EstimatorCamera> cameras{2};

  // The first 50 frames (2.5 s) keep the test short; the static start
  // initialises after about 1 s.
  explicit StereoReplay(int frames = 50) : seq(ExcerptOf(dir, frames)) {
    options = ReadEstimatorOptions(root);
    ApplyImuConfig(imu, &options);
    for (int c = 0; c < 2; ++c) {
      cameras[c].T_b_c.linear() = seq.cameras[c].q_b_c.toRotationMatrix();
      cameras[c].T_b_c.translation() = seq.cameras[c].t_b_c;
      cameras[c].focal_px = CameraModel(seq.cameras[c]).focal();
    }
  }
  Estimator MakeEstimator() const {
    return Estimator(options, ReadVisualOptions(root), seq.imu.noise,
                     imu.preintegration, cameras);
  }
  // Frames tracked while the estimator consumes them, as vio_replay does:
  // the image lists and the IMU read from their files as the run goes.
  std::vector<EstimatorOutput> Streamed(const PipelineOptions& pipeline,
                                        ImageTrackingSummary* summary) const {
    Estimator estimator = MakeEstimator();
    // Pipelined as vio_replay: reading and tracking on their own threads.
    EurocImageStream stream(seq, frontend, true, !pipeline.sequential);
    ImuStampReport counts;
    ImuCsvStream imu(seq.data.imu_path, &counts);
    StreamingRunner runner(&estimator,
                           [&imu](ImuSample* s) { return imu.Next(s); });
    std::vector<EstimatorOutput> outputs;
    RunFramePipeline(
        [&](FeatureFrame* f) { return stream.Next(f); },
        [&](FeatureFrame&& f) { outputs.push_back(runner.AddFrame(f)); },
        pipeline);
    *summary = stream.summary();
    return outputs;
  }
};

void ExpectIdentical(const std::vector<EstimatorOutput>& a,
                     const std::vector<EstimatorOutput>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(std::string(what) + ", frame " + std::to_string(i));
    EXPECT_EQ(a[i].t_ns, b[i].t_ns);
    EXPECT_EQ(a[i].processed, b[i].processed);
    EXPECT_EQ(a[i].initialized, b[i].initialized);
    EXPECT_EQ(a[i].keyframe, b[i].keyframe);
    EXPECT_EQ(a[i].zero_velocity, b[i].zero_velocity);
    // Exact equality: the same inputs in the same order.
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(a[i].p_w_b[k], b[i].p_w_b[k]);
      EXPECT_EQ(a[i].v_w[k], b[i].v_w[k]);
      EXPECT_EQ(a[i].b_a[k], b[i].b_a[k]);
      EXPECT_EQ(a[i].b_g[k], b[i].b_g[k]);
    }
    EXPECT_EQ(a[i].q_w_b.coeffs(), b[i].q_w_b.coeffs());
  }
}

TEST(ImageReplay, PipelinedEqualsSequentialBitForBitOnRealStereo) {
  const StereoReplay replay;
  // Today's order: every image tracked first, then the estimator.
  ImageTrackingSummary all_first;
  const std::vector<FeatureFrame> frames =
      ImageObservations(replay.seq, replay.frontend, &all_first);
  // The image list read as the frames go gives the one read at load.
  const std::vector<ImageEntry>& listed = replay.seq.data.cameras[0].images;
  ASSERT_EQ(frames.size(), listed.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].t_ns, listed[k].t_ns);
  }
  Estimator estimator = replay.MakeEstimator();
  const std::vector<EstimatorOutput> expected =
      RunSequence(&estimator, replay.seq.data.imu, frames);

  PipelineOptions pipelined;
  pipelined.queue_frames = 2;  // the frontend blocks on the estimator often
  ImageTrackingSummary images;
  const std::vector<EstimatorOutput> outputs =
      replay.Streamed(pipelined, &images);
  ExpectIdentical(expected, outputs, "pipelined");
  EXPECT_EQ(images.frames, 50);
  EXPECT_EQ(images.stereo_frames, all_first.stereo_frames);
  EXPECT_EQ(images.observations[0], all_first.observations[0]);
  EXPECT_EQ(images.observations[1], all_first.observations[1]);
  EXPECT_EQ(images.cameras[1].missing, 4);

  PipelineOptions sequential;
  sequential.sequential = true;
  ExpectIdentical(expected, replay.Streamed(sequential, &images), "sequential");
  // Not vacuous: the run initialised and estimated most frames.
  int initialised = 0;
  for (const EstimatorOutput& o : outputs) initialised += o.initialized;
  EXPECT_GE(initialised, 25);
}

// The threaded stream (reading, tracking, matching on three threads) gives
// the frames of one thread bit for bit, with the same counts, and can be
// dropped half way without hanging (the threads are blocked on full queues
// then).
TEST(EurocImageStream, ThreadedGivesTheFramesOfOneThreadBitForBit) {
  const StereoReplay replay(30);
  EurocImageStream one(replay.seq, replay.frontend, true, false);
  EurocImageStream threaded(replay.seq, replay.frontend, true, true);
  FeatureFrame a, b;
  int frames = 0;
  while (one.Next(&a)) {
    ASSERT_TRUE(threaded.Next(&b)) << "frame " << frames;
    ASSERT_EQ(a.t_ns, b.t_ns);
    ASSERT_EQ(a.observations.size(), b.observations.size());
    for (size_t i = 0; i < a.observations.size(); ++i) {
      const FeatureObservation& p = a.observations[i];
      const FeatureObservation& q = b.observations[i];
      EXPECT_EQ(p.feature_id, q.feature_id);
      EXPECT_EQ(p.camera, q.camera);
      EXPECT_EQ(p.uv, q.uv);
      EXPECT_EQ(p.xy, q.xy);
      EXPECT_EQ(p.velocity, q.velocity);
    }
    ++frames;
  }
  EXPECT_FALSE(threaded.Next(&b));
  EXPECT_FALSE(threaded.Next(&b));  // and stays at the end
  EXPECT_EQ(frames, 30);
  for (int c = 0; c < 2; ++c) {
    EXPECT_EQ(one.summary().cameras[c].used,
              threaded.summary().cameras[c].used);
    EXPECT_EQ(one.summary().cameras[c].missing,
              threaded.summary().cameras[c].missing);
    EXPECT_EQ(one.summary().cameras[c].unpaired,
              threaded.summary().cameras[c].unpaired);
  }
  EXPECT_EQ(one.summary().observations[1], threaded.summary().observations[1]);
  EXPECT_EQ(one.builder_summary().observations,
            threaded.builder_summary().observations);

  EurocImageStream dropped(replay.seq, replay.frontend, true, true);
  ASSERT_TRUE(dropped.Next(&b));
}

}  // namespace
}  // namespace vio
