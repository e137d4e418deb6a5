// The whole image pipeline in motion, as vio_sim --render and vio_replay run
// it: a short simulated sequence rendered (textured room, blur, gain,
// vignetting, noise), tracked by the frontend, turned into observations and
// replayed through the estimator; it must initialise on the still start and
// stay on the simulator's truth. Also the folder vio_sim --render writes:
// what the EuRoC reader and the image tracker read back from it.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "config/euroc_sequence.h"
#include "config/frontend_config.h"
#include "dataset/sim_folder.h"
#include "dataset/sim_trajectory.h"
#include "frontend/image_frontend.h"
#include "frontend/observation_builder.h"
#include "render/scene_file.h"
#include "render/sequence_renderer.h"
#include "render/texture_atlas.h"
#include "test/testing/sim_replay.h"
#include "test/testing/temp_folder.h"
#include "tools/image_tracks.h"
#include "tools/sim_images.h"

namespace vio {
namespace {

// 3.5 s: 1.2 s still (the static start needs 1 s), a 0.8 s blend, then the
// default ellipse at up to 1.3 m/s.
SimulatorOptions ShortMovingSequence() {
  SimulatorOptions o;
  o.duration_s = 3.5;
  o.motion.still_duration_s = 1.2;
  o.motion.blend_duration_s = 0.8;
  return o;
}

BodyPoseAt PoseOf(const SimulatorOptions& o) {
  return TrajectoryBodyPose(std::make_shared<SimTrajectory>(o.motion),
                            o.start_time_ns, o.duration_s);
}

SceneLayout Room(const Simulation& sim, std::vector<int>* left_out) {
  const SimRoomOptions& r = sim.options.room;
  return LayoutClearOfPath({-r.half_length_x_m, -r.half_width_y_m, 0.0},
                           {r.half_length_x_m, r.half_width_y_m, r.height_m},
                           RenderOptions().boxes, SimulationPath(sim), 0.5,
                           left_out);
}

TEST(RenderReplay, ARenderedSequenceInMotionInitialisesAndStaysOnTheTruth) {
  const Simulation sim = Simulate(ShortMovingSequence());
  std::vector<int> left_out;
  RenderOptions render;
  render.view_scale = 0.75;  // twice as fast; the frontend copes
  const TexturedScene scene =
      MakeTexturedScene(MakeRoomScene(Room(sim, &left_out)),
                        LoadTextureCrops(BuiltInTextureFolder()), render, 1);
  const CameraCalibration& cam0 = sim.options.camera.cam0;
  SequenceRenderer renderer({cam0}, &scene, render, 0.0, 1);
  FrontendOptions frontend = LoadFrontendOptions(std::string(VIO_SOURCE_DIR) +
                                                 "/config/euroc_mono.yaml");
  frontend.tracker.max_features = 100;
  ImageFrontend tracker(CameraModel(cam0), nullptr, frontend);
  ObservationBuilder builder({CameraModel(cam0)});
  std::vector<FeatureFrame> frames;
  RenderedFrame image;
  const BodyPoseAt pose = PoseOf(sim.options);
  for (const FeatureFrame& f : sim.frames) {
    renderer.Render(f.t_ns, pose, &image);
    frames.push_back(tracker.Process(f.t_ns, image.images[0]));
    builder.Process(&frames.back());
  }
  EXPECT_GT(renderer.stats().max_blur_samples, 1) << "blurred in motion";
  const testing::SimReplay r =
      testing::Replay(sim, testing::OptionsFor(sim.options), sim.imu, frames);
  const auto first = std::find_if(r.outputs.begin(), r.outputs.end(),
                                  [](const auto& o) { return o.initialized; });
  ASSERT_NE(first, r.outputs.end()) << "never initialised";
  EXPECT_LT(first - r.outputs.begin(), 30) << "the still start is 1.2 s";
  EXPECT_EQ(r.summary.resets, 0);
  // Measured 0.0029 m (the simulator's features.csv of the same sequence,
  // 1 px noise: 0.0150 m).
  EXPECT_LT(r.ate_rmse_m, 0.02);
  std::printf("frames %zu, initialised after %td, ATE %.4f m\n", frames.size(),
              first - r.outputs.begin(), r.ate_rmse_m);
}

TEST(RenderReplay, TheRenderedFolderReadsLikeARecordedSequence) {
  SimulatorOptions o = ShortMovingSequence();
  o.duration_s = 0.3;  // 7 frames
  o.camera.stereo = true;
  const Simulation sim = Simulate(o);
  testing::TempFolder folder;
  SimulationFolderOptions content;
  content.write_features = false;
  WriteSimulationFolder(sim, folder.path(), content);
  std::vector<int> left_out;
  const SimImagesSummary summary = RenderSimulationImages(
      sim, Room(sim, &left_out), RenderOptions(), PoseOf(o), folder.path());
  EXPECT_EQ(summary.render.frames, 7);
  EXPECT_EQ(summary.render.images, 14);

  const EurocSequence seq = LoadEurocSequence(folder.path());
  ASSERT_EQ(seq.data.cameras.size(), 2u);
  for (const EurocCamera& camera : seq.data.cameras) {
    EXPECT_TRUE(camera.has_images);
    EXPECT_FALSE(camera.has_features);
    ASSERT_EQ(camera.images.size(), sim.frames.size());
    for (size_t i = 0; i < sim.frames.size(); ++i) {
      EXPECT_EQ(camera.images[i].t_ns, sim.frames[i].t_ns);
    }
  }
  // The PNGs hold exactly what a renderer with the same seed draws.
  const TexturedScene scene = MakeTexturedScene(
      MakeRoomScene(Room(sim, &left_out)),
      LoadTextureCrops(BuiltInTextureFolder()), RenderOptions(), o.seed);
  SequenceRenderer renderer({o.camera.cam0, o.camera.cam1}, &scene,
                            RenderOptions(), 0.0, o.seed);
  RenderedFrame frame;
  for (size_t i = 0; i < sim.frames.size(); ++i) {
    renderer.Render(sim.frames[i].t_ns, PoseOf(o), &frame);
    for (int c = 0; c < 2; ++c) {
      const cv::Mat png =
          cv::imread(seq.data.cameras[c].images[i].path, cv::IMREAD_UNCHANGED);
      ASSERT_EQ(png.type(), CV_8UC1);
      EXPECT_EQ(cv::norm(png, frame.images[c], cv::NORM_INF), 0.0);
    }
  }
  // The truth files: the scene and a pose per frame.
  ASSERT_TRUE(HasRenderTruth(folder.path()));
  const RenderTruth truth = ReadRenderTruth(folder.path());
  EXPECT_EQ(truth.scene.planes().size(),
            6u + 5u * (RenderOptions().boxes.size() - left_out.size()));
  ASSERT_EQ(truth.frame_poses.size(), sim.frames.size());
  EXPECT_LT((truth.frame_poses.back().p_w_b - frame.T_w_b.translation()).norm(),
            1e-8);
  // The image tracker (vio_track, vio_replay) reads it: every frame stereo.
  ImageTrackingSummary tracking;
  const std::vector<FeatureFrame> tracked =
      TrackEurocImages(seq, FrontendOptions(), &tracking);
  EXPECT_EQ(tracking.frames, 7);
  EXPECT_EQ(tracking.stereo_frames, 7);
  EXPECT_EQ(tracking.skipped(), 0);
}

}  // namespace
}  // namespace vio
