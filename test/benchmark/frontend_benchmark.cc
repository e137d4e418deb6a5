// Time per frame of the frontend on the real EuRoC V1_01 excerpt (752x480
// stereo pairs, decoded into memory first so that PNG decoding is not
// counted). CPU time is the whole process's (OpenCV may use worker
// threads). Run: ./build/test/benchmark/frontend_benchmark

#include <benchmark/benchmark.h>

#include <vector>

#include "frontend/image_frontend.h"
#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

struct Frames {
  std::vector<int64_t> t_ns;
  std::vector<cv::Mat> left, right;
};

const Frames& RealFrames() {
  static const Frames frames = [] {
    Frames f;
    const auto rows = testing::V101ImageList(0);
    for (size_t k = 0; k < rows.size(); ++k) {
      f.t_ns.push_back(rows[k].first);
      f.left.push_back(testing::V101Image(0, k));
      f.right.push_back(testing::V101Image(1, k));
    }
    return f;
  }();
  return frames;
}

// One iteration = one frame, cycling through the 95 real frames.
void RunFrontend(benchmark::State& state, const FrontendOptions& options) {
  const Frames& frames = RealFrames();
  if (frames.left.empty() || frames.left[0].empty()) {
    state.SkipWithError("cannot read the V1_01 excerpt");
    return;
  }
  const CameraModel cam0(testing::V101Cam0()), cam1(testing::V101Cam1());
  ImageFrontend frontend(cam0, &cam1, options);
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        frontend.Process(frames.t_ns[k], frames.left[k], frames.right[k]));
    k = (k + 1) % frames.left.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["frames_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}

void BM_FrontendMono(benchmark::State& state) {
  FrontendOptions options;
  options.stereo = false;
  RunFrontend(state, options);
}

void BM_FrontendStereo(benchmark::State& state) {
  RunFrontend(state, FrontendOptions());
}

void BM_FrontendStereoClahe(benchmark::State& state) {
  FrontendOptions options;
  options.tracker.clahe = true;
  RunFrontend(state, options);
}

BENCHMARK(BM_FrontendMono)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK(BM_FrontendStereo)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK(BM_FrontendStereoClahe)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();

}  // namespace
}  // namespace vio

BENCHMARK_MAIN();
