#include "dataset/euroc_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "dataset/csv.h"
#include "dataset/features_csv.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using ::testing::HasSubstr;
using testing::TempFolder;

const std::string kV101 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s";
const std::string kMh05 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_MH_05_imu_gt";

constexpr char kImuHeader[] =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],"
    "w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],"
    "a_RS_S_z [m s^-2]\n";
constexpr char kImuRows[] =
    "1000000000,0.1,0.2,0.3,9.8,0.0,0.1\n"
    "1005000000,0.1,0.2,0.3,9.8,0.0,0.1\n"
    "1010000000,0.1,0.2,0.3,9.8,0.0,0.1\n";

// Expects `f` to throw DatasetError whose message contains every one of
// `texts`.
template <typename F>
void ExpectDatasetError(F f, std::initializer_list<std::string> texts) {
  try {
    f();
    ADD_FAILURE() << "no DatasetError";
  } catch (const DatasetError& e) {
    for (const std::string& text : texts) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  }
}

// A minimal valid sequence: IMU, one camera with two images (one listed but
// missing), ground truth.
void WriteValidSequence(const TempFolder& dir) {
  dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + kImuRows);
  dir.Write("mav0/cam0/data.csv",
            "#timestamp [ns],filename\n"
            "1000000000,1000000000.png\n"
            "1050000000,1050000000.png\n"
            "1100000000,1100000000.png\n");
  dir.Write("mav0/cam0/data/1000000000.png", "not really a png");
  dir.Write("mav0/cam0/data/1100000000.png", "not really a png");
  dir.Write("mav0/state_groundtruth_estimate0/data.csv",
            "#timestamp,p,p,p,q,q,q,q,v,v,v,bw,bw,bw,ba,ba,ba\n"
            "999000000,1,2,3,1,0,0,0,0,0,0,0.01,0,0,0.1,0,0\n"
            "1004000000,1,2,3,1,0,0,0,0,0,0,0.01,0,0,0.1,0,0\n");
}

TEST(EurocReader, ReadsAFixtureSequenceAndCountsMissingImages) {
  TempFolder dir;
  WriteValidSequence(dir);
  const EurocData data = ReadEurocFolder(dir.path());
  ASSERT_EQ(data.imu.size(), 3u);
  EXPECT_EQ(data.imu[1].t_ns, 1005000000);
  EXPECT_EQ(data.imu[1].gyr, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(data.imu[1].acc, Eigen::Vector3d(9.8, 0.0, 0.1));
  ASSERT_EQ(data.cameras.size(), 1u);
  EXPECT_TRUE(data.cameras[0].has_images);
  EXPECT_FALSE(data.cameras[0].has_features);
  ASSERT_EQ(data.cameras[0].images.size(), 2u);
  EXPECT_EQ(data.cameras[0].images[1].t_ns, 1100000000);
  EXPECT_EQ(data.cameras[0].images[1].path,
            dir.Path("mav0/cam0/data/1100000000.png"));
  EXPECT_EQ(data.cameras[0].missing_images, 1);
  ASSERT_EQ(data.ground_truth.size(), 2u);
  EXPECT_EQ(data.start_ns, 999000000);  // ground truth starts first here
  EXPECT_DOUBLE_EQ(data.SecondsSinceStart(1100000000), 0.101);
}

TEST(EurocReader, MissingFolderFileOrCameraContentIsAnError) {
  TempFolder dir;
  ExpectDatasetError([&] { ReadEurocFolder(dir.Path("nope")); },
                     {dir.Path("nope"), "no such folder"});
  ExpectDatasetError([&] { ReadEurocFolder(dir.path()); },
                     {"not a EuRoC sequence folder (no mav0/ inside)"});
  WriteValidSequence(dir);
  dir.Remove("mav0/imu0/data.csv");
  ExpectDatasetError([&] { ReadEurocFolder(dir.path()); },
                     {"mav0/imu0/data.csv: no such file"});
  WriteValidSequence(dir);
  dir.Remove("mav0/cam0/data.csv");
  ExpectDatasetError(
      [&] { ReadEurocFolder(dir.path()); },
      {"mav0/cam0: holds neither data.csv (images) nor features.csv"});
}

// Each bad IMU file, and the text its error must contain.
struct BadFile {
  const char* rows;
  const char* message;
};

TEST(EurocReader, EveryBadImuLineNamesFileAndLine) {
  // Strict or not: malformed lines are errors. Stamps that do not increase
  // are errors only in a strict read (see the next two tests).
  struct Case {
    const char* rows;
    const char* message;
    bool strict;
  };
  const Case cases[] = {
      {"1000000000,0.1,0.2,0.3,9.8,0.0\n",
       "data.csv:2: expected 7 fields, got 6", false},
      {"1000000000,0.1,0.2,0.3,9.8,0.0,0.1,7\n",
       "data.csv:2: expected 7 fields (timestamp, 3 angular rates, 3 "
       "accelerations), got 8",
       false},
      {"1000000000,0.1,0.2,abc,9.8,0.0,0.1\n",
       "data.csv:2: field 4 is not a number ('abc')", false},
      {"10x0000000,0.1,0.2,0.3,9.8,0.0,0.1\n",
       "data.csv:2: field 1 is not an integer ('10x0000000')", false},
      {"1000000000,0.1,nan,0.3,9.8,0.0,0.1\n",
       "data.csv:2: field 3 is not finite ('nan')", false},
      {"1000000000,0.1,0.2,0.3,9.8,0.0,0.1\n"
       "1000000000,0.1,0.2,0.3,9.8,0.0,0.1\n",
       "data.csv:3: timestamp 1000000000 is repeated", true},
      {"1000000000,0.1,0.2,0.3,9.8,0.0,0.1\n"
       "\n"
       "990000000,0.1,0.2,0.3,9.8,0.0,0.1\n",
       "data.csv:4: timestamp 990000000 is before the previous one "
       "(1000000000)",
       true},
      {"", "data.csv: holds no IMU sample", false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    TempFolder dir;
    WriteValidSequence(dir);
    dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + c.rows);
    EurocReadOptions options;
    options.strict = c.strict;
    ExpectDatasetError([&] { ReadEurocFolder(dir.path(), options); },
                       {dir.Path("mav0/imu0/") + c.message});
  }
}

// Lines 2..9 of an IMU file: a repeated line (4), a repeated stamp with
// other values (6), a sample from the past (8) and one stamped far in the
// future (9, before the samples that follow it).
constexpr char kMessyImuRows[] =
    "1000000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 2
    "1005000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 3
    "1005000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 4 exact repeat
    "1010000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 5
    "1010000000,0.5,0.2,0.3,9.8,0.0,0.1\n"   // 6 same stamp, other values
    "1015000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 7
    "1001000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 8 before the last
    "9000000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 9 runs ahead
    "1020000000,0.1,0.2,0.3,9.8,0.0,0.1\n"   // 10
    "1025000000,0.1,0.2,0.3,9.8,0.0,0.1\n";  // 11

TEST(EurocReader, RepeatedAndDisorderedImuStampsAreDroppedAndCounted) {
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + kMessyImuRows);
  const EurocData data = ReadEurocFolder(dir.path());
  const std::vector<int64_t> expected = {1000000000, 1005000000, 1010000000,
                                         1015000000, 1020000000, 1025000000};
  ASSERT_EQ(data.imu.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(data.imu[i].t_ns, expected[i]) << i;
  }
  // The first of the two samples at 1010000000 is the one kept.
  EXPECT_DOUBLE_EQ(data.imu[2].gyr.x(), 0.1);
  const ImuStampReport& r = data.imu_stamps;
  EXPECT_EQ(r.repeated_lines, 1);
  EXPECT_EQ(r.first_repeated_line, 4);
  EXPECT_EQ(r.conflicting_repeats, 1);
  EXPECT_EQ(r.first_conflict_line, 6);
  EXPECT_EQ(r.first_conflict_t_ns, 1010000000);
  EXPECT_EQ(r.out_of_order, 2);
  EXPECT_EQ(r.first_out_of_order_line, 8);
  EXPECT_EQ(r.dropped(), 4);
}

TEST(EurocReader, StrictReadRefusesTheFirstStampThatDoesNotIncrease) {
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + kMessyImuRows);
  EurocReadOptions strict;
  strict.strict = true;
  ExpectDatasetError(
      [&] { ReadEurocFolder(dir.path(), strict); },
      {dir.Path("mav0/imu0/data.csv:4: timestamp 1005000000 is repeated")});
}

TEST(EurocReader, EveryBadImageListLineNamesFileAndLine) {
  const BadFile cases[] = {
      {"1000000000\n", "data.csv:2: expected 2 fields, got 1"},
      {"1000000000,a.png,b.png\n",
       "data.csv:2: expected 2 fields (timestamp, filename), got 3"},
      {"1000000000,\n", "data.csv:2: the filename is empty"},
      {"abc,a.png\n", "data.csv:2: field 1 is not an integer ('abc')"},
      {"1000000000,a.png\n1000000000,b.png\n",
       "data.csv:3: timestamp 1000000000 is repeated"},
      {"1000000000,a.png\n900000000,b.png\n",
       "data.csv:3: timestamp 900000000 is before the previous one"},
  };
  for (const BadFile& c : cases) {
    SCOPED_TRACE(c.message);
    TempFolder dir;
    WriteValidSequence(dir);
    dir.Write("mav0/cam0/data.csv",
              std::string("#timestamp [ns],filename\n") + c.rows);
    ExpectDatasetError([&] { ReadEurocFolder(dir.path()); },
                       {dir.Path("mav0/cam0/") + c.message});
  }
}

TEST(EurocReader, EveryBadFeaturesLineNamesFileAndLine) {
  const BadFile cases[] = {
      {"1000000000,3,10.5\n", "features.csv:2: expected 4 fields, got 3"},
      {"1000000000,3,10.5,20.5,1\n",
       "features.csv:2: expected 4 fields (timestamp, feature_id, u, v), got "
       "5"},
      {"1000000000,3,10.5,inf\n", "features.csv:2: field 4 is not finite"},
      {"1000000000,3.5,10.5,20.5\n",
       "features.csv:2: field 2 is not an integer ('3.5')"},
      {"1000000000,-1,10.5,20.5\n",
       "features.csv:2: feature_id must be >= 0 (got -1)"},
      {"1000000000,3,10.5,20.5\n1000000000,3,11.5,20.5\n",
       "features.csv:3: feature_id 3 appears twice at timestamp 1000000000"},
      {"1000000000,3,10.5,20.5\n900000000,4,11.5,20.5\n",
       "features.csv:3: timestamp 900000000 is before the previous one "
       "(1000000000)"},
  };
  for (const BadFile& c : cases) {
    SCOPED_TRACE(c.message);
    TempFolder dir;
    WriteValidSequence(dir);
    dir.Write(
        "mav0/cam1/features.csv",
        std::string("#timestamp [ns],feature_id,u [px],v [px]\n") + c.rows);
    ExpectDatasetError([&] { ReadEurocFolder(dir.path()); },
                       {dir.Path("mav0/cam1/") + c.message});
  }
}

TEST(EurocReader, BadGroundTruthLineNamesFileAndLine) {
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Write("mav0/state_groundtruth_estimate0/data.csv",
            "#header\n999000000,1,2,3,1,0,0,0,0,0,0\n");
  ExpectDatasetError(
      [&] { ReadEurocFolder(dir.path()); },
      {dir.Path("mav0/state_groundtruth_estimate0/data.csv:2: expected 17 "
                "fields, got 11")});
}

TEST(EurocReader, ReadsACameraFolderThatHoldsFeaturesInsteadOfImages) {
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Write("mav0/cam1/features.csv",
            "#timestamp [ns],feature_id,u [px],v [px]\n"
            "1000000000,3,10.5,20.25\n"
            "1000000000,7,11.5,21.25\n"
            "1050000000,3,12.5,22.25\n");
  const EurocData data = ReadEurocFolder(dir.path());
  ASSERT_EQ(data.cameras.size(), 2u);
  const EurocCamera& cam1 = data.cameras[1];
  EXPECT_FALSE(cam1.has_images);
  EXPECT_TRUE(cam1.has_features);
  ASSERT_EQ(cam1.feature_frames.size(), 2u);
  EXPECT_EQ(cam1.feature_frames[0].t_ns, 1000000000);
  ASSERT_EQ(cam1.feature_frames[0].observations.size(), 2u);
  const FeatureObservation& obs = cam1.feature_frames[0].observations[1];
  EXPECT_EQ(obs.feature_id, 7);
  EXPECT_EQ(obs.camera, 1);
  EXPECT_EQ(obs.uv, Eigen::Vector2d(11.5, 21.25));
  EXPECT_EQ(cam1.feature_frames[1].observations.size(), 1u);
}

FeatureObservation Observation(int64_t id, int camera, double u, double v) {
  FeatureObservation obs;
  obs.feature_id = id;
  obs.camera = camera;
  obs.uv = {u, v};
  return obs;
}

TEST(EurocReader, FeaturesCsvRoundTripsThroughWriterAndReader) {
  TempFolder dir;
  std::vector<FeatureFrame> frames(2);
  frames[0].t_ns = 1403715273262142976;
  frames[1].t_ns = 1403715273312143104;
  frames[0].observations = {Observation(5, 0, 1.25, 2.5),
                            Observation(5, 1, 3.0, 4.0),  // other camera
                            Observation(9, 0, 751.123456, 479.654321)};
  frames[1].observations = {Observation(9, 0, 700.0, 400.0)};
  WriteFeaturesCsv(dir.Path("f.csv"), frames, 0);
  const std::vector<FeatureFrame> back = ReadFeaturesCsv(dir.Path("f.csv"), 0);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].t_ns, frames[0].t_ns);
  EXPECT_EQ(back[1].t_ns, frames[1].t_ns);
  ASSERT_EQ(back[0].observations.size(), 2u);
  EXPECT_EQ(back[0].observations[1].feature_id, 9);
  EXPECT_EQ(back[0].observations[1].uv,
            Eigen::Vector2d(751.123456, 479.654321));
}

TEST(EurocReader, LoadsTheRealV101ExcerptWithItsMissingCam1Images) {
  const EurocData data = ReadEurocFolder(kV101);
  ASSERT_EQ(data.cameras.size(), 2u);
  EXPECT_EQ(data.cameras[0].images.size(), 95u);
  EXPECT_EQ(data.cameras[0].missing_images, 0);
  EXPECT_EQ(data.cameras[1].images.size(), 95u);
  EXPECT_EQ(data.cameras[1].missing_images, 4);
  EXPECT_EQ(data.cameras[0].images.front().t_ns, 1403715273262142976);
  // The whole sequence's IMU: 145.6 s at 200 Hz.
  EXPECT_EQ(data.imu.size(), 29120u);
  EXPECT_EQ(data.imu.front().t_ns, 1403715273262142976);
  EXPECT_NEAR(data.SecondsSinceStart(data.imu.back().t_ns), 145.6, 0.05);
  EXPECT_NEAR(data.imu.front().acc.x(), 9.0874956666666655, 1e-15);
  ASSERT_EQ(data.ground_truth.size(), 2895u);
  EXPECT_EQ(data.ground_truth.front().t_ns, 1403715273262142976);
  EXPECT_NEAR(data.ground_truth.front().p_w_b.x(), 0.878895, 1e-12);
  EXPECT_EQ(data.start_ns, 1403715273262142976);
  // 20 Hz images: the 95 stamps span 94 periods of 50 ms.
  EXPECT_NEAR(data.SecondsSinceStart(data.cameras[0].images.back().t_ns), 4.7,
              1e-6);
}

TEST(EurocReader, AFolderWithoutImuLoadsOnlyWhenTheCallerSaysSo) {
  // The real MH_01 excerpt: moving stereo images, no imu0/ at all.
  const std::string mh01 =
      std::string(VIO_SHARED_DIR) + "/data/euroc_MH_01_moving_6s";
  ExpectDatasetError(
      [&] { ReadEurocFolder(mh01); },
      {"euroc_MH_01_moving_6s/mav0/imu0/data.csv: no such file"});
  EurocReadOptions options;
  options.require_imu = false;
  const EurocData data = ReadEurocFolder(mh01, options);
  EXPECT_FALSE(data.has_imu);
  EXPECT_TRUE(data.imu.empty());
  ASSERT_EQ(data.cameras.size(), 2u);
  EXPECT_EQ(data.cameras[0].images.size(), 120u);
  EXPECT_EQ(data.cameras[1].images.size(), 120u);
  EXPECT_EQ(data.start_ns, data.cameras[0].images.front().t_ns);
  // An imu0/ folder without its data.csv stays an error either way.
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Remove("mav0/imu0/data.csv");
  ExpectDatasetError([&] { ReadEurocFolder(dir.path(), options); },
                     {"mav0/imu0/data.csv: no such file"});
  // With an IMU the option changes nothing.
  WriteValidSequence(dir);
  EXPECT_TRUE(ReadEurocFolder(dir.path(), options).has_imu);
  EXPECT_EQ(ReadEurocFolder(dir.path(), options).imu.size(), 3u);
}

// vio_replay's read: the IMU and the image lists checked through at load but
// not kept. Every count, first stamp and error is that of the kept read.
TEST(EurocReader, NotKeepingTheImuAndImageListsChangesOnlyTheVectors) {
  EurocReadOptions streamed;
  streamed.keep_imu = false;
  streamed.keep_image_lists = false;
  const EurocData kept = ReadEurocFolder(kV101);
  const EurocData data = ReadEurocFolder(kV101, streamed);
  EXPECT_TRUE(data.imu.empty());
  EXPECT_EQ(data.imu_path, kV101 + "/mav0/imu0/data.csv");
  EXPECT_EQ(data.imu_count, 29120);
  EXPECT_EQ(data.imu_count, static_cast<int64_t>(kept.imu.size()));
  EXPECT_EQ(data.imu_first_ns, kept.imu.front().t_ns);
  EXPECT_EQ(kept.imu_first_ns, kept.imu.front().t_ns);
  EXPECT_EQ(data.start_ns, kept.start_ns);
  ASSERT_EQ(data.cameras.size(), 2u);
  for (int c = 0; c < 2; ++c) {
    EXPECT_TRUE(data.cameras[c].images.empty());
    EXPECT_EQ(data.cameras[c].image_count, 95);
    EXPECT_EQ(kept.cameras[c].image_count, 95);
    EXPECT_EQ(data.cameras[c].first_image_ns,
              kept.cameras[c].images.front().t_ns);
    EXPECT_EQ(data.cameras[c].missing_images, kept.cameras[c].missing_images);
  }
  // The stamp filter's counts, on a messy file.
  TempFolder dir;
  WriteValidSequence(dir);
  dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + kMessyImuRows);
  const EurocData messy = ReadEurocFolder(dir.path(), streamed);
  EXPECT_EQ(messy.imu_count, 6);
  EXPECT_EQ(messy.imu_first_ns, 1000000000);
  EXPECT_EQ(messy.imu_stamps.dropped(), 4);
  EXPECT_EQ(messy.imu_stamps.first_out_of_order_line, 8);
  EXPECT_EQ(messy.cameras[0].image_count, 2);
  EXPECT_EQ(messy.cameras[0].first_image_ns, 1000000000);
  EXPECT_EQ(messy.cameras[0].missing_images, 1);
  EXPECT_EQ(messy.start_ns, 999000000);
  // Errors anywhere in the files are still found at load.
  dir.Write("mav0/imu0/data.csv", std::string(kImuHeader) + kImuRows +
                                      "1015000000,0.1,0.2,0.3,9.8,inf,0.1\n");
  ExpectDatasetError(
      [&] { ReadEurocFolder(dir.path(), streamed); },
      {dir.Path("mav0/imu0/data.csv:5: field 6 is not finite ('inf')")});
  WriteValidSequence(dir);
  dir.Write("mav0/cam0/data.csv",
            "#timestamp [ns],filename\n1000000000,a.png\n900000000,b.png\n");
  ExpectDatasetError([&] { ReadEurocFolder(dir.path(), streamed); },
                     {dir.Path("mav0/cam0/data.csv:3: timestamp 900000000 is "
                               "before the previous one")});
}

TEST(EurocReader, LoadsTheRealMh05ExcerptThatHasNoCameraFolder) {
  const EurocData data = ReadEurocFolder(kMh05);
  EXPECT_TRUE(data.cameras.empty());
  EXPECT_EQ(data.imu.size(), 22721u);
  EXPECT_EQ(data.ground_truth.size(), 22212u);
  EXPECT_EQ(data.start_ns, data.imu.front().t_ns);
  EXPECT_LT(data.imu.front().t_ns, data.ground_truth.front().t_ns);
}

}  // namespace
}  // namespace vio
