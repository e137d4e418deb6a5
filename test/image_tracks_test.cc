#include "tools/image_tracks.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>

#include "dataset/features_csv.h"
#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

namespace fs = std::filesystem;

std::string V101Sequence() {
  return std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s";
}

TEST(TrackEurocImages, RealStereoSequenceCountsTheMissingCam1Images) {
  const EurocSequence sequence = LoadEurocSequence(V101Sequence());
  ImageTrackingSummary summary;
  const std::vector<FeatureFrame> frames =
      TrackEurocImages(sequence, FrontendOptions(), &summary);
  EXPECT_EQ(frames.size(), 95u);
  EXPECT_EQ(summary.frames, 95);
  EXPECT_EQ(summary.stereo_frames, 95);
  EXPECT_EQ(summary.cameras[0].used, 95);
  EXPECT_EQ(summary.cameras[1].used, 95);
  EXPECT_EQ(summary.cameras[1].missing, 4);
  EXPECT_EQ(summary.skipped(), 4);
  EXPECT_GT(summary.observations[1], summary.observations[0] / 3);
  for (size_t k = 1; k < frames.size(); ++k) {
    EXPECT_GT(frames[k].t_ns, frames[k - 1].t_ns);
  }
}

// A small sequence folder made from real files, with one image of each kind
// of fault in cam0 and cam1.
class BadImages : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path src = fs::path(V101Sequence()) / "mav0";
    // A folder per test: ctest runs the fixture's tests in parallel.
    root_ = fs::path(::testing::TempDir()) /
            (std::string("vio_bad_images_") +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    const fs::path mav0 = root_ / "mav0";
    fs::create_directories(mav0 / "imu0");
    fs::copy_file(src / "imu0/sensor.yaml", mav0 / "imu0/sensor.yaml");
    // The first second of IMU is enough for a folder that loads.
    std::ifstream imu_in(src / "imu0/data.csv");
    std::ofstream imu_out(mav0 / "imu0/data.csv");
    std::string line;
    for (int i = 0; i < 250 && std::getline(imu_in, line); ++i) {
      imu_out << line << "\n";
    }
    for (int c = 0; c < 2; ++c) {
      const std::string cam = "cam" + std::to_string(c);
      fs::create_directories(mav0 / cam / "data");
      fs::copy_file(src / cam / "sensor.yaml", mav0 / cam / "sensor.yaml");
      const auto rows = testing::V101ImageList(c);
      std::ofstream csv(mav0 / cam / "data.csv");
      csv << "#timestamp [ns],filename\n";
      for (int k = 0; k < 6; ++k) {
        csv << rows[k].first << "," << rows[k].second << "\n";
        const fs::path to = mav0 / cam / "data" / rows[k].second;
        // cam0: frame 2 unreadable, 4 missing; cam1: 3 wrong size, 5 missing.
        if ((c == 0 && k == 4) || (c == 1 && k == 5)) continue;
        if (c == 0 && k == 2) {
          std::ofstream(to) << "not a PNG";
        } else if (c == 1 && k == 3) {
          cv::imwrite(to.string(), cv::Mat(240, 376, CV_8UC1, cv::Scalar(9)));
        } else {
          fs::copy_file(src / cam / "data" / rows[k].second, to);
        }
      }
    }
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
};

TEST_F(BadImages, AreSkippedAndCountedNeverFatal) {
  const EurocSequence sequence = LoadEurocSequence(root_.string());
  ImageTrackingSummary summary;
  const std::vector<FeatureFrame> frames =
      TrackEurocImages(sequence, FrontendOptions(), &summary);
  // cam0 frames 0, 1, 3, 5 are good; cam1 pairs with 0, 1 (3: wrong size,
  // 5: missing); cam1 frames 2 and 4 lose their cam0 partner.
  EXPECT_EQ(frames.size(), 4u);
  EXPECT_EQ(summary.cameras[0].missing, 1);
  EXPECT_EQ(summary.cameras[0].unreadable, 1);
  EXPECT_EQ(summary.cameras[0].used, 4);
  EXPECT_EQ(summary.cameras[1].missing, 1);
  EXPECT_EQ(summary.cameras[1].wrong_size, 1);
  EXPECT_EQ(summary.cameras[1].unpaired, 2);
  EXPECT_EQ(summary.cameras[1].used, 2);
  EXPECT_EQ(summary.stereo_frames, 2);
  EXPECT_EQ(summary.skipped(), 4);
}

// cam1's list is walked alongside cam0's by stamp: its images before cam0's
// first, between two of cam0's and after cam0's last are all counted as
// without a partner, whatever the frames read so far.
TEST_F(BadImages, Cam1ImagesWithoutACam0PartnerAnywhereAreCounted) {
  const fs::path cam1 = root_ / "mav0/cam1";
  const auto rows = testing::V101ImageList(1);
  std::ofstream csv(cam1 / "data.csv", std::ios::trunc);
  csv << "#timestamp [ns],filename\n";
  // Before cam0's first, then cam0's 0 and 1, between 1 and 2, after 5.
  csv << rows[0].first - 1 << "," << rows[0].second << "\n";
  csv << rows[0].first << "," << rows[0].second << "\n";
  csv << rows[1].first << "," << rows[1].second << "\n";
  csv << rows[1].first + 1 << "," << rows[1].second << "\n";
  csv << rows[5].first + 1 << "," << rows[0].second << "\n";
  csv << rows[5].first + 2 << "," << rows[1].second << "\n";
  csv.close();
  const EurocSequence sequence = LoadEurocSequence(root_.string());
  ImageTrackingSummary summary;
  const std::vector<FeatureFrame> frames =
      TrackEurocImages(sequence, FrontendOptions(), &summary);
  EXPECT_EQ(frames.size(), 4u);
  EXPECT_EQ(summary.cameras[1].used, 2);
  EXPECT_EQ(summary.stereo_frames, 2);
  EXPECT_EQ(summary.cameras[1].unpaired, 4);
  EXPECT_EQ(summary.cameras[1].missing, 0);
  EXPECT_EQ(summary.cameras[0].missing, 1);
}

TEST(SaveTracks, OneFeaturesCsvPerCameraThatReadsBack) {
  EXPECT_EQ(TracksPathForCamera("out/tracks.csv", 0), "out/tracks.csv");
  EXPECT_EQ(TracksPathForCamera("out/tracks.csv", 1), "out/tracks.cam1.csv");
  EXPECT_EQ(TracksPathForCamera("out.d/tracks", 1), "out.d/tracks.cam1");

  std::vector<FeatureFrame> frames(2);
  frames[0].t_ns = 100;
  frames[1].t_ns = 200;
  FeatureObservation a, b;
  a.feature_id = 3;
  a.uv = {10.25, 20.5};
  b = a;
  b.camera = 1;
  b.uv = {4.0, 20.75};
  frames[0].observations = {a, b};
  a.uv = {11.0, 21.0};
  frames[1].observations = {a};
  const std::string path = ::testing::TempDir() + "/vio_tracks.csv";
  const auto files = SaveTracks(path, frames, 2);
  ASSERT_EQ(files.size(), 2u);
  const auto cam0 = ReadFeaturesCsv(files[0], 0);
  const auto cam1 = ReadFeaturesCsv(files[1], 1);
  ASSERT_EQ(cam0.size(), 2u);
  ASSERT_EQ(cam1.size(), 1u);
  EXPECT_EQ(cam0[1].t_ns, 200);
  EXPECT_EQ(cam0[1].observations[0].uv, Eigen::Vector2d(11.0, 21.0));
  EXPECT_EQ(cam1[0].observations[0].feature_id, 3);
  EXPECT_EQ(cam1[0].observations[0].uv, Eigen::Vector2d(4.0, 20.75));
  std::remove(files[0].c_str());
  std::remove(files[1].c_str());
}

}  // namespace
}  // namespace vio
