// Time per image of the renderer (render/), one OpenCV thread, 752x480 EuRoC
// cam0, along the default preset's trajectory in its textured room; and, in
// the same run for a load-independent ratio, the mono frontend on the
// rendered images. The rates are per CPU second of the benchmark's thread
// (Google Benchmark's kIsRate divides by CPU time), so they hold under load.
// Run: ./build/test/benchmark/render_benchmark

#include <benchmark/benchmark.h>

#include <memory>
#include <opencv2/core/utility.hpp>
#include <vector>

#include "dataset/sim_trajectory.h"
#include "dataset/simulator.h"
#include "frontend/image_frontend.h"
#include "render/camera_renderer.h"
#include "render/sensor_model.h"
#include "render/sequence_renderer.h"
#include "render/texture_atlas.h"

namespace vio {
namespace {

constexpr int64_t kStartNs = 1600000000000000000;

const TexturedScene& Scene() {
  static const TexturedScene scene = [] {
    SceneLayout layout;
    layout.boxes = DefaultSceneBoxes();
    return MakeTexturedScene(MakeRoomScene(layout),
                             LoadTextureCrops(BuiltInTextureFolder()),
                             RenderOptions(), 1);
  }();
  return scene;
}

BodyPoseAt PresetPose(const SimMotionOptions& motion) {
  auto trajectory = std::make_shared<SimTrajectory>(motion);
  return [trajectory](int64_t t_ns) {
    const SimState s = trajectory->At((t_ns - kStartNs) * 1e-9);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = s.q_w_b.toRotationMatrix();
    T.translation() = s.p_w_b;
    return T;
  };
}

// The frame stamps of the preset after its still start, 20 Hz.
int64_t Stamp(size_t k) { return kStartNs + 4000000000LL + 50000000LL * k; }

// One image without blur: the warps, the distortion remap, the sensor.
void RenderOneImage(benchmark::State& state, double view_scale) {
  cv::setNumThreads(1);
  const CameraCalibration c = EurocCam0Calibration();
  RenderOptions options;
  options.view_scale = view_scale;
  const CameraRenderer renderer(c, &Scene(), view_scale);
  const SensorModel sensor(c, options);
  const BodyPoseAt pose = PresetPose(SimMotionOptions());
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
  T_b_c.linear() = c.q_b_c.toRotationMatrix();
  T_b_c.translation() = c.t_b_c;
  cv::Mat radiance, image;
  size_t k = 0;
  for (auto _ : state) {
    renderer.RenderRadiance({pose(Stamp(k)) * T_b_c}, &radiance);
    sensor.Expose(radiance, 1.0, k, &image);
    benchmark::DoNotOptimize(image.data);
    k = (k + 1) % 720;
  }
  state.counters["images_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}

void BM_RenderImage(benchmark::State& state) { RenderOneImage(state, 1.0); }
void BM_RenderImageViewScale075(benchmark::State& state) {
  RenderOneImage(state, 0.75);
}

// A preset's frames with its render options (motion blur included).
void RenderPreset(benchmark::State& state, const SimMotionOptions& motion) {
  cv::setNumThreads(1);
  SequenceRenderer renderer({EurocCam0Calibration()}, &Scene(), RenderOptions(),
                            0.0, 1);
  const BodyPoseAt pose = PresetPose(motion);
  RenderedFrame frame;
  size_t k = 0;
  for (auto _ : state) {
    renderer.Render(Stamp(k), pose, &frame);
    benchmark::DoNotOptimize(frame.images[0].data);
    k = (k + 1) % 720;
  }
  state.counters["images_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
  state.counters["blur_renders"] =
      static_cast<double>(renderer.stats().blur_samples) /
      renderer.stats().frames;
}

void BM_RenderDefaultPreset(benchmark::State& state) {
  RenderPreset(state, SimMotionOptions());
}

void BM_RenderAggressivePreset(benchmark::State& state) {
  SimMotionOptions m;  // config/sim_aggressive.yaml's motion
  m.still_duration_s = 1.0;
  m.blend_duration_s = 1.5;
  m.lap_period_s = 7.0;
  m.height_amplitude_m = 0.6;
  m.roll_amplitude_rad = m.pitch_amplitude_rad = 0.35;
  m.yaw_amplitude_rad = 0.6;
  RenderPreset(state, m);
}

// The reference: the mono frontend on 100 rendered default-preset images.
void BM_FrontendMonoOnRenderedImages(benchmark::State& state) {
  cv::setNumThreads(1);
  SequenceRenderer renderer({EurocCam0Calibration()}, &Scene(), RenderOptions(),
                            0.0, 1);
  const BodyPoseAt pose = PresetPose(SimMotionOptions());
  std::vector<cv::Mat> images;
  RenderedFrame frame;
  for (size_t k = 0; k < 100; ++k) {
    renderer.Render(Stamp(k), pose, &frame);
    images.push_back(frame.images[0].clone());
  }
  FrontendOptions options;
  options.stereo = false;
  ImageFrontend frontend(CameraModel(EurocCam0Calibration()), nullptr, options);
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(frontend.Process(Stamp(k), images[k % 100]));
    ++k;
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_RenderImage)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderImageViewScale075)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderDefaultPreset)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderAggressivePreset)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrontendMonoOnRenderedImages)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vio

BENCHMARK_MAIN();
