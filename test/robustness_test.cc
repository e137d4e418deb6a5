// The table of docs/robustness.md as regression tests: one bad moment in an
// 8 s simulated sequence (the default preset's motion, as vio_replay runs it)
// must not end or ruin the run. Each fault is put at several places and of
// several sizes; every run must give a pose to as many frames as the clean
// run and an ATE close to the clean run's.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/fault_injection.h"
#include "dataset/sim_folder.h"
#include "test/testing/sim_replay.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using testing::SimReplay;

const Simulation& Sequence() {
  static const Simulation* simulation =
      new Simulation(Simulate(testing::ShortSimulation(8.0, false)));
  return *simulation;
}

EstimatorOptions Options() { return testing::OptionsFor(Sequence().options); }

int64_t FramesWithPose(const SimReplay& r) {
  int64_t n = 0;
  for (const EstimatorOutput& o : r.outputs) {
    n += o.processed && o.initialized ? 1 : 0;
  }
  return n;
}

SimReplay Faulted(const std::vector<ImuSample>& imu,
                  const std::vector<FeatureFrame>& frames,
                  const EstimatorOptions& options = Options()) {
  return testing::Replay(Sequence(), options, imu, frames);
}

const SimReplay& Clean() {
  static const SimReplay* clean = new SimReplay(
      Faulted(Sequence().imu, testing::Prepare(Sequence()).frames));
  return *clean;
}

// One line per run, so that ctest -V shows the figures of the table.
void Report(const std::string& what, const SimReplay& r) {
  std::printf("%-52s poses %lld/%lld visual %lld resets %lld ATE %.4f m\n",
              what.c_str(), static_cast<long long>(FramesWithPose(r)),
              static_cast<long long>(r.summary.frames),
              static_cast<long long>(r.summary.frames_visual_only),
              static_cast<long long>(r.summary.resets), r.ate_rmse_m);
}

// As many frames with a pose as the clean run (all after the static start),
// and an ATE within `ratio` of the clean run's.
void ExpectLikeTheCleanRun(const SimReplay& r, double ratio) {
  EXPECT_EQ(FramesWithPose(r), FramesWithPose(Clean()));
  EXPECT_GT(r.ate_rmse_m, 0.0);
  EXPECT_LT(r.ate_rmse_m, ratio * Clean().ate_rmse_m);
  for (const EstimatorOutput& o : r.outputs) {
    ASSERT_TRUE(o.p_w_b.allFinite() && o.v_w.allFinite()) << o.t_ns;
  }
}

ImuFault Fault(ImuFaultKind kind, double t_s, int count, double value = 0.0) {
  ImuFault f;
  f.kind = kind;
  f.t_s = t_s;
  f.count = count;
  f.value = value;
  return f;
}

TEST(Robustness, CleanRunIsTheReference) {
  Report("clean", Clean());
  // All 142 frames after the static start (19 before it); measured 0.037 m.
  EXPECT_EQ(FramesWithPose(Clean()),
            Clean().summary.frames - Clean().summary.frames_before_init);
  EXPECT_LT(Clean().ate_rmse_m, 0.06);
}

// Runs each fault and expects the gap bridged on vision, no reset, and a
// run like the clean one.
void ExpectGapsBridged(const std::vector<ImuFault>& faults, double ratio) {
  const std::vector<FeatureFrame> frames = testing::Prepare(Sequence()).frames;
  for (const ImuFault& fault : faults) {
    const SimReplay r = Faulted(WithImuFault(Sequence().imu, fault), frames);
    Report(fault.Describe(), r);
    SCOPED_TRACE(fault.Describe());
    ExpectLikeTheCleanRun(r, ratio);
    EXPECT_EQ(r.summary.resets, 0);
    ASSERT_EQ(r.summary.imu_gaps.size(), 1u);
    const ImuGap& gap = r.summary.imu_gaps[0];
    EXPECT_NEAR(gap.length_s(), 0.005 * (fault.count + 1), 1e-9);
    EXPECT_GT(gap.frames_visual, 0);
    EXPECT_EQ(gap.frames_visual, r.summary.frames_visual_only);
    EXPECT_EQ(gap.frames_lost, 0);
  }
}

// Before: every frame after the gap was skipped (80 poses of 161); the gap
// is now crossed on vision alone and the IMU taken up again after it.
// Measured 0.036 m (5 samples) and 0.039 m (100) against the clean 0.037 m.
TEST(Robustness, ImuGapsWhileTurningAreBridgedOnVision) {
  ExpectGapsBridged({Fault(ImuFaultKind::kDrop, 4.93, 5),
                     Fault(ImuFaultKind::kDrop, 4.93, 100)},
                    1.3);
}

// Measured 0.037 m (0.5 s at 6.5 s) and 0.056 m (2 s at 4.93 s: 41 frames
// on vision alone) against the clean 0.037 m.
TEST(Robustness, LongerAndLaterImuGapsAreBridgedOnVision) {
  ExpectGapsBridged({Fault(ImuFaultKind::kDrop, 6.5, 100),
                     Fault(ImuFaultKind::kDrop, 4.93, 400)},
                    2.0);
}

TEST(Robustness, ShortGapsAreIntegratedAcrossAndCounted) {
  // Three missing samples: a 20 ms step, max_sample_gap itself.
  const SimReplay r =
      Faulted(WithImuFault(Sequence().imu, Fault(ImuFaultKind::kDrop, 4.93, 3)),
              testing::Prepare(Sequence()).frames);
  Report("3 samples dropped", r);
  EXPECT_EQ(r.summary.imu_short_gaps, 1);
  EXPECT_TRUE(r.summary.imu_gaps.empty());
  EXPECT_EQ(r.summary.frames_visual_only, 0);
  ExpectLikeTheCleanRun(r, 1.1);
}

void ExpectGlitchesReplaced(const std::vector<ImuFault>& faults) {
  const std::vector<FeatureFrame> frames = testing::Prepare(Sequence()).frames;
  for (const ImuFault& fault : faults) {
    const SimReplay r = Faulted(WithImuFault(Sequence().imu, fault), frames);
    Report(fault.Describe(), r);
    SCOPED_TRACE(fault.Describe());
    EXPECT_EQ(r.summary.imu_replaced, fault.count);
    EXPECT_EQ(r.summary.resets, 0);
    // The neighbours' interpolation is within the noise of the replaced
    // samples: measured the clean run's ATE to 0.6 mm.
    ExpectLikeTheCleanRun(r, 1.05);
  }
}

// Before: 1e308 stopped the program in Ceres (exit 134).
TEST(Robustness, AGyroscopeValueOf1e308IsReplaced) {
  ExpectGlitchesReplaced({Fault(ImuFaultKind::kGyroValue, 4.93, 1, 1e308),
                          Fault(ImuFaultKind::kGyroValue, 6.5, 1, -1e308)});
}

// Before: an ATE of 4.8 km, nothing said about the input.
TEST(Robustness, AnAccelerometerValueOf1e6IsReplaced) {
  ExpectGlitchesReplaced({Fault(ImuFaultKind::kAccelValue, 6.5, 1, 1e6),
                          Fault(ImuFaultKind::kAccelValue, 3.0, 3, -400.0)});
}

// Before: an ATE of 0.87 m and a reset.
TEST(Robustness, AGyroscopeValueOf1000RadPerSecondIsReplaced) {
  ExpectGlitchesReplaced({Fault(ImuFaultKind::kGyroValue, 4.93, 1, 1000.0)});
}

// The estimator's own guard, with the range check off (a range no sample
// leaves): the glitch reaches the preintegration, and the state it makes is
// never handed to Ceres.
TEST(Robustness, AnExplodingStateIsResetNeverSolved) {
  EstimatorOptions options = Options();
  options.imu_stream.range.accelerometer_range =
      std::numeric_limits<double>::max();
  options.imu_stream.range.gyroscope_range = std::numeric_limits<double>::max();
  const std::vector<FeatureFrame> frames = testing::Prepare(Sequence()).frames;
  for (const ImuFault& fault :
       {Fault(ImuFaultKind::kGyroValue, 4.93, 1, 1e308),
        Fault(ImuFaultKind::kAccelValue, 4.93, 1, 1e6)}) {
    const SimReplay r =
        Faulted(WithImuFault(Sequence().imu, fault), frames, options);
    Report(fault.Describe() + " (no range check)", r);
    SCOPED_TRACE(fault.Describe());
    EXPECT_EQ(r.summary.imu_replaced, 0);
    ASSERT_GE(r.summary.resets, 1);
    EXPECT_EQ(r.summary.reset_log[0].reason, Failure::kUnsafeState);
    EXPECT_EQ(FramesWithPose(r), FramesWithPose(Clean()));
    for (const EstimatorOutput& o : r.outputs) {
      ASSERT_TRUE(o.p_w_b.allFinite() && o.v_w.allFinite()) << o.t_ns;
    }
  }
}

// Before: "timestamp ... is repeated", exit 1. The reader drops the repeated
// and the disordered lines, so the estimator sees the clean stream.
TEST(Robustness, RepeatedAndDisorderedImuLinesAreDroppedByTheReader) {
  testing::TempFolder dir;
  WriteSimulationFolder(Sequence(), dir.path());
  const std::vector<ImuSample> clean = ReadEurocFolder(dir.path()).imu;
  const std::string path = dir.Path("mav0/imu0/data.csv");
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  std::string csv = text.str();
  csv = WithImuFaultInCsv(csv, Fault(ImuFaultKind::kRepeat, 4.93, 1));
  csv = WithImuFaultInCsv(csv, Fault(ImuFaultKind::kBackwards, 6.5, 3));
  std::ofstream(path) << csv;

  const EurocData data = ReadEurocFolder(dir.path());
  EXPECT_EQ(data.imu_stamps.repeated_lines, 1);
  EXPECT_EQ(data.imu_stamps.out_of_order, 1);
  // The clean stream less the one sample moved out of order.
  ASSERT_EQ(data.imu.size() + 1, clean.size());
  EXPECT_EQ(data.imu.front().t_ns, clean.front().t_ns);
  EXPECT_EQ(data.imu.back().t_ns, clean.back().t_ns);
  const SimReplay r = Faulted(data.imu, testing::Prepare(Sequence()).frames);
  Report("IMU line repeated, one sample out of order", r);
  ExpectLikeTheCleanRun(r, 1.05);
  EurocReadOptions strict;
  strict.strict = true;
  EXPECT_THROW(ReadEurocFolder(dir.path(), strict), DatasetError);
}

// Before: used or dropped without a trace.
TEST(Robustness, ObservationsOutsideTheImageAreCountedAsSkipped) {
  std::vector<FeatureFrame> raw = Sequence().frames;
  SetObservationPixels(&raw, 4.0, 30, Eigen::Vector2d(-300.0, 200.0));
  SetObservationPixels(&raw, 6.0, 30, Eigen::Vector2d(1e6, 200.0));
  const testing::PreparedSimulation prepared =
      testing::Prepare(Sequence(), raw);
  EXPECT_EQ(prepared.removed.outside_image, 60);
  const SimReplay r = Faulted(Sequence().imu, prepared.frames);
  Report("60 observations outside the image", r);
  ExpectLikeTheCleanRun(r, 1.2);
}

// Vision cannot place a frame while the vehicle still stands (no landmark
// has parallax yet): those frames get no pose, and the window starts afresh
// when the IMU returns.
TEST(Robustness, AGapVisionCannotBridgeEndsInARestartAfterIt) {
  // 1.2 s: after the static start (it needs 1 s of stillness spanned by the
  // frames, so it comes at 1.0-1.05 s) and well before the motion (2 s), so
  // the whole gap falls on a standing monocular window.
  const SimReplay r = Faulted(
      WithImuFault(Sequence().imu, Fault(ImuFaultKind::kDrop, 1.2, 100)),
      testing::Prepare(Sequence()).frames);
  Report("100 IMU samples dropped at 1.2 s (standing still)", r);
  ASSERT_EQ(r.summary.imu_gaps.size(), 1u);
  const ImuGap& gap = r.summary.imu_gaps[0];
  EXPECT_TRUE(gap.reset);
  EXPECT_EQ(gap.frames_lost, 10);
  ASSERT_EQ(r.summary.resets, 1);
  EXPECT_EQ(r.summary.reset_log[0].reason, Failure::kImuGap);
  EXPECT_EQ(FramesWithPose(r), FramesWithPose(Clean()) - 10);
  EXPECT_LT(r.ate_rmse_m, 2.0 * Clean().ate_rmse_m);
}

}  // namespace
}  // namespace vio
