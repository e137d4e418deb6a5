#include "dataset/frame_faults.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace vio {
namespace {

constexpr int64_t kStart = 1600000000000000000LL;
constexpr int64_t kPeriod = 50000000LL;  // 20 Hz

// 100 stereo frames at 20 Hz from kStart (5 s), 20 features each in cam0
// and cam1, feature i at pixel (i, frame).
std::vector<FeatureFrame> Frames() {
  std::vector<FeatureFrame> frames(100);
  for (int k = 0; k < 100; ++k) {
    frames[k].t_ns = kStart + kPeriod * k;
    for (int cam = 0; cam < 2; ++cam) {
      for (int i = 0; i < 20; ++i) {
        FeatureObservation o;
        o.feature_id = i;
        o.camera = cam;
        o.uv = Eigen::Vector2d(i, k);
        frames[k].observations.push_back(o);
      }
    }
  }
  return frames;
}

FrameFault Fault(FrameFaultKind kind, double t_s, double duration_s) {
  FrameFault f;
  f.kind = kind;
  f.t_s = t_s;
  f.duration_s = duration_s;
  return f;
}

std::set<int64_t> Stamps(const std::vector<FeatureFrame>& frames) {
  std::set<int64_t> stamps;
  for (const FeatureFrame& f : frames) stamps.insert(f.t_ns);
  return stamps;
}

TEST(WithFrameFault, BlackoutRemovesEveryFrameOfItsSpanAndNoOther) {
  const std::vector<FeatureFrame> f = WithFrameFault(
      Frames(), Fault(FrameFaultKind::kBlackout, 1.0, 2.0), kStart);
  ASSERT_EQ(f.size(), 60u);  // frames 20..59 gone
  for (const FeatureFrame& frame : f) {
    const int64_t k = (frame.t_ns - kStart) / kPeriod;
    EXPECT_TRUE(k < 20 || k >= 60) << k;
    EXPECT_EQ(frame.observations.size(), 40u);
  }
}

TEST(WithFrameFault, HalfRateKeepsEverySecondFrameFromItsStart) {
  const std::vector<FeatureFrame> f = WithFrameFault(
      Frames(), Fault(FrameFaultKind::kHalfRate, 2.0, 0.0), kStart);
  ASSERT_EQ(f.size(), 70u);  // 40 before, 30 of the 60 after
  const std::set<int64_t> stamps = Stamps(f);
  for (int k = 0; k < 100; ++k) {
    const bool kept = k < 40 || (k - 40) % 2 == 0;
    EXPECT_EQ(stamps.count(kStart + kPeriod * k), kept ? 1u : 0u) << k;
  }
}

TEST(WithFrameFault, EmptyFramesTakeTheirShareOfTheSpanOnly) {
  FrameFault fault = Fault(FrameFaultKind::kEmptyFrames, 1.0, 3.0);
  fault.fraction = 0.3;
  const std::vector<FeatureFrame> f = WithFrameFault(Frames(), fault, kStart);
  const std::set<int64_t> stamps = Stamps(f);
  int lost = 0;
  for (int k = 0; k < 100; ++k) {
    const bool present = stamps.count(kStart + kPeriod * k) == 1;
    if (k < 20 || k >= 80) {
      EXPECT_TRUE(present) << k;
    }
    if (!present) ++lost;
  }
  // 60 frames in the span, 30 % of them: 18 expected, binomial sd 3.5.
  EXPECT_GE(lost, 9);
  EXPECT_LE(lost, 27);
  // The same seed gives the same frames; another seed others.
  EXPECT_EQ(Stamps(WithFrameFault(Frames(), fault, kStart)), stamps);
  fault.seed = 2;
  EXPECT_NE(Stamps(WithFrameFault(Frames(), fault, kStart)), stamps);
  // Twice the share, twice the frames: 36 expected, sd 3.8.
  fault.fraction = 0.6;
  const size_t kept = WithFrameFault(Frames(), fault, kStart).size();
  EXPECT_GE(100 - static_cast<int>(kept), 28);
  EXPECT_LE(100 - static_cast<int>(kept), 44);
}

TEST(WithFrameFault, OutliersMoveTheirShareOfObservationsInsideTheImage) {
  FrameFault fault = Fault(FrameFaultKind::kOutliers, 1.0, 2.0);
  fault.fraction = 0.4;
  fault.width = 752;
  fault.height = 480;
  const std::vector<FeatureFrame> clean = Frames();
  const std::vector<FeatureFrame> f = WithFrameFault(clean, fault, kStart);
  ASSERT_EQ(f.size(), clean.size());
  int moved = 0, in_span = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    ASSERT_EQ(f[k].t_ns, clean[k].t_ns);
    ASSERT_EQ(f[k].observations.size(), clean[k].observations.size());
    for (size_t i = 0; i < f[k].observations.size(); ++i) {
      const FeatureObservation& o = f[k].observations[i];
      EXPECT_EQ(o.feature_id, clean[k].observations[i].feature_id);
      EXPECT_EQ(o.camera, clean[k].observations[i].camera);
      const bool changed = o.uv != clean[k].observations[i].uv;
      if (k < 20 || k >= 60) {
        EXPECT_FALSE(changed) << k;
        continue;
      }
      ++in_span;
      if (!changed) continue;
      ++moved;
      EXPECT_GE(o.uv.x(), 0);
      EXPECT_LE(o.uv.x(), 751);
      EXPECT_GE(o.uv.y(), 0);
      EXPECT_LE(o.uv.y(), 479);
    }
  }
  // 1600 observations in the span, 40 % of them: 640, binomial sd 20.
  ASSERT_EQ(in_span, 1600);
  EXPECT_GT(moved, 560);
  EXPECT_LT(moved, 720);
}

TEST(WithFrameFault, TimeOffsetMovesEveryStampAndNothingElse) {
  FrameFault fault;
  fault.kind = FrameFaultKind::kTimeOffset;
  fault.offset_s = 0.025;
  const std::vector<FeatureFrame> clean = Frames();
  const std::vector<FeatureFrame> f = WithFrameFault(clean, fault, kStart);
  ASSERT_EQ(f.size(), clean.size());
  for (size_t k = 0; k < f.size(); ++k) {
    EXPECT_EQ(f[k].t_ns, clean[k].t_ns + 25000000) << k;
    ASSERT_EQ(f[k].observations.size(), clean[k].observations.size());
    EXPECT_EQ(f[k].observations[7].uv, clean[k].observations[7].uv);
  }
}

TEST(WithFrameFault, AFaultThatDoesNotFitIsRefused) {
  // Beyond the frames, a zero span, a share out of range, no image size.
  EXPECT_THROW(
      WithFrameFault(Frames(), Fault(FrameFaultKind::kBlackout, 6.0, 2.0),
                     kStart),
      std::invalid_argument);
  EXPECT_THROW(
      WithFrameFault(Frames(), Fault(FrameFaultKind::kBlackout, 1.0, 0.0),
                     kStart),
      std::invalid_argument);
  FrameFault outliers = Fault(FrameFaultKind::kOutliers, 1.0, 1.0);
  outliers.fraction = 1.5;
  outliers.width = outliers.height = 100;
  EXPECT_THROW(WithFrameFault(Frames(), outliers, kStart),
               std::invalid_argument);
  outliers.fraction = 0.4;
  outliers.width = 0;
  EXPECT_THROW(WithFrameFault(Frames(), outliers, kStart),
               std::invalid_argument);
  std::string message;
  EXPECT_FALSE(outliers.Validate(&message));
  EXPECT_NE(message.find("width"), std::string::npos) << message;
}

}  // namespace
}  // namespace vio
