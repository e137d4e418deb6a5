#include "frontend/image_frontend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>
#include <vector>

#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

// The real excerpt (vehicle on the ground) through the stereo frontend at
// 10 Hz (every other frame, to keep the test fast): tracks live long, keep
// their ids, and move together. The image content drifts by about 1.7 px
// over the 4.7 s (the vehicle settles), the same for every track of the
// rigid scene, so each track's displacement must match the median one.
// (The recomputed ground truth turns by 3.6 mrad over the excerpt but mostly
// about the optical axis, which does not match the image motion; at this
// level it is not a reference, so it is not used here.)
TEST(ImageFrontend, RealSequenceTracksLiveLongAndMoveTogether) {
  const CameraModel cam0(testing::V101Cam0()), cam1(testing::V101Cam1());
  ImageFrontend frontend(cam0, &cam1, FrontendOptions());
  ASSERT_TRUE(frontend.stereo());
  const auto rows = testing::V101ImageList(0);
  ASSERT_EQ(rows.size(), 95u);
  std::map<int64_t, Eigen::Vector2d> first_uv, last_uv;  // cam0
  for (size_t k = 0; k < rows.size(); k += 2) {
    const FeatureFrame frame = frontend.Process(
        rows[k].first, testing::V101Image(0, k), testing::V101Image(1, k));
    EXPECT_EQ(frame.t_ns, rows[k].first);
    std::set<int64_t> ids[2];
    for (const FeatureObservation& o : frame.observations) {
      ASSERT_TRUE(o.camera == 0 || o.camera == 1);
      EXPECT_TRUE(ids[o.camera].insert(o.feature_id).second);
      if (o.camera != 0) continue;
      if (k == 0) first_uv[o.feature_id] = o.uv;
      if (k + 1 == rows.size()) last_uv[o.feature_id] = o.uv;
    }
    for (int64_t id : ids[1]) EXPECT_TRUE(ids[0].count(id)) << "orphan right";
    EXPECT_GE(ids[0].size(), 140u) << "frame " << k;
    EXPECT_GE(ids[1].size(), 0.4 * ids[0].size()) << "frame " << k;
    EXPECT_TRUE(frontend.stats().stereo_matched);
  }
  std::vector<Eigen::Vector2d> moves;
  for (const auto& [id, uv] : first_uv) {
    auto it = last_uv.find(id);
    if (it != last_uv.end()) moves.push_back(it->second - uv);
  }
  ASSERT_GE(moves.size(), 0.7 * first_uv.size());
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::vector<double> du, dv;
  for (const Eigen::Vector2d& m : moves) {
    du.push_back(m.x());
    dv.push_back(m.y());
  }
  const Eigen::Vector2d common(median(du), median(dv));
  std::vector<double> deviation;
  for (const Eigen::Vector2d& m : moves)
    deviation.push_back((m - common).norm());
  std::sort(deviation.begin(), deviation.end());
  std::printf(
      "%zu of %zu tracks span the sequence; common motion (%.2f, "
      "%.2f) px; deviation from it median %.2f px, p90 %.2f px\n",
      moves.size(), first_uv.size(), common.x(), common.y(),
      deviation[deviation.size() / 2], deviation[deviation.size() * 9 / 10]);
  EXPECT_LT(deviation[deviation.size() / 2], 0.35);       // measured 0.23
  EXPECT_LT(deviation[deviation.size() * 9 / 10], 0.75);  // measured 0.48
}

TEST(ImageFrontend, MissingRightImageGivesALeftOnlyFrame) {
  const CameraModel cam0(testing::V101Cam0()), cam1(testing::V101Cam1());
  ImageFrontend frontend(cam0, &cam1, FrontendOptions());
  const FeatureFrame frame = frontend.Process(7, testing::V101Image(0, 0));
  EXPECT_FALSE(frontend.stats().stereo_matched);
  ASSERT_FALSE(frame.observations.empty());
  for (const FeatureObservation& o : frame.observations) EXPECT_EQ(o.camera, 0);
}

TEST(ImageFrontend, StereoNeedsTheRightCalibration) {
  const CameraModel cam0(testing::V101Cam0());
  EXPECT_THROW(ImageFrontend(cam0, nullptr, FrontendOptions()),
               std::invalid_argument);
  FrontendOptions mono;
  mono.stereo = false;
  ImageFrontend frontend(cam0, nullptr, mono);
  EXPECT_FALSE(frontend.stereo());
  FrontendOptions invalid;
  invalid.tracker.max_features = 0;
  EXPECT_THROW(ImageFrontend(cam0, nullptr, invalid), std::invalid_argument);
}

// A rectified pair (no distortion, cam1 0.11 m to the right of cam0): the
// right image is the left one moved left by a disparity that grows by 7 px
// a frame to 91 px. Unguided, the 15 px window's three pyramid levels reach
// a few tens of px from the left pixel; started from the previous frame's
// offset, each match is 7 px from its start and keeps being found.
int MatchesAtTheEndOfAGrowingDisparity(bool start_from_previous) {
  CameraCalibration c0 = testing::V101Cam0();
  c0.distortion = DistortionModel::kNone;
  CameraCalibration c1 = c0;
  c1.t_b_c = c0.t_b_c + c0.q_b_c * Eigen::Vector3d(0.11, 0.0, 0.0);
  const CameraModel cam0(c0), cam1(c1);
  FrontendOptions options;
  options.stereo_matcher.start_from_previous = start_from_previous;
  ImageFrontend frontend(cam0, &cam1, options);
  const cv::Mat left = testing::V101Image(0, 0);
  int matched = 0;
  for (int k = 1; k <= 13; ++k) {
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -7.0 * k, 0, 1, 0);
    cv::Mat right;
    cv::warpAffine(left, right, shift, left.size(), cv::INTER_NEAREST,
                   cv::BORDER_REPLICATE);
    frontend.Process(k, left, right);
    matched = frontend.stats().stereo.matched;
  }
  return matched;
}

TEST(ImageFrontend, StartFromPreviousFollowsAGrowingDisparity) {
  const int guided = MatchesAtTheEndOfAGrowingDisparity(true);
  const int unguided = MatchesAtTheEndOfAGrowingDisparity(false);
  std::printf(
      "matches at 91 px of disparity: %d from the previous offset, "
      "%d from the left pixel\n",
      guided, unguided);
  EXPECT_GE(guided, 80);
  EXPECT_LT(unguided, guided / 2);
}

}  // namespace
}  // namespace vio
