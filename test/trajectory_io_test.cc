#include "dataset/trajectory_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "dataset/csv.h"

namespace vio {
namespace {

using ::testing::HasSubstr;

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "trajectory_io_test_" + name;
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

// The DatasetError message of reading `text` with `reader`, or "" if none.
template <typename Reader>
std::string ErrorOf(const std::string& name, const std::string& text,
                    Reader reader) {
  const std::string path = WriteFile(name, text);
  try {
    reader(path);
  } catch (const DatasetError& e) {
    return e.what();
  }
  return "";
}

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

std::vector<StampedState> RandomStates(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  std::vector<StampedState> states;
  int64_t t_ns = 1403638519492829440LL;  // an EuRoC stamp
  for (int i = 0; i < count; ++i) {
    StampedState s;
    t_ns += 5000000 + i;  // 5 ms plus odd nanoseconds
    s.t_ns = t_ns;
    s.p_w_b = {u(rng), u(rng), u(rng)};
    s.q_w_b = RandomRotation(rng);
    s.v_w = {u(rng), u(rng), u(rng)};
    s.b_a = {u(rng) / 100, u(rng) / 100, u(rng) / 100};
    s.b_g = {u(rng) / 1000, u(rng) / 1000, u(rng) / 1000};
    states.push_back(s);
  }
  return states;
}

// q and -q are one rotation.
void ExpectSameRotation(const Eigen::Quaterniond& a,
                        const Eigen::Quaterniond& b, double tol) {
  EXPECT_NEAR(std::abs(a.dot(b)), 1.0, tol);
}

TEST(TrajectoryIo, TumRoundTripKeepsNanosecondStampsAndPoses) {
  std::mt19937 rng(42);
  Trajectory written;
  for (const StampedState& s : RandomStates(rng, 50))
    written.push_back(PoseOf(s));
  written.front().t_ns = -1500000001;  // negative stamps survive too
  const std::string path = TempPath("round_trip.txt");
  WriteTum(path, written);
  const Trajectory read = ReadTum(path);
  ASSERT_EQ(read.size(), written.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].t_ns, written[i].t_ns) << i;
    // The writer keeps 9 significant digits: 20 m -> 1e-7 m.
    EXPECT_LT((read[i].p_w_b - written[i].p_w_b).norm(), 1e-6) << i;
    ExpectSameRotation(read[i].q_w_b, written[i].q_w_b, 1e-8);
  }
}

TEST(TrajectoryIo, StateCsvRoundTripKeepsEveryField) {
  std::mt19937 rng(7);
  const std::vector<StampedState> written = RandomStates(rng, 30);
  const std::string path = TempPath("round_trip.csv");
  WriteStateCsv(path, written);
  const std::vector<StampedState> read = ReadEurocGroundTruth(path);
  ASSERT_EQ(read.size(), written.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].t_ns, written[i].t_ns);
    EXPECT_LT((read[i].p_w_b - written[i].p_w_b).norm(), 1e-6);
    ExpectSameRotation(read[i].q_w_b, written[i].q_w_b, 1e-8);
    EXPECT_LT((read[i].v_w - written[i].v_w).norm(), 1e-6);
    EXPECT_LT((read[i].b_a - written[i].b_a).norm(), 1e-9);
    EXPECT_LT((read[i].b_g - written[i].b_g).norm(), 1e-10);
  }
}

TEST(TrajectoryIo, ReadTrajectoryTellsTumFromEurocByContent) {
  std::mt19937 rng(3);
  const std::vector<StampedState> states = RandomStates(rng, 5);
  Trajectory poses;
  for (const StampedState& s : states) poses.push_back(PoseOf(s));
  // The extension says nothing: both files are named .txt.
  const std::string tum = TempPath("detect_tum.txt");
  const std::string csv = TempPath("detect_csv.txt");
  WriteTum(tum, poses);
  WriteStateCsv(csv, states);
  for (const std::string& path : {tum, csv}) {
    const Trajectory read = ReadTrajectory(path);
    ASSERT_EQ(read.size(), poses.size()) << path;
    for (size_t i = 0; i < read.size(); ++i) {
      EXPECT_EQ(read[i].t_ns, poses[i].t_ns) << path;
      EXPECT_LT((read[i].p_w_b - poses[i].p_w_b).norm(), 1e-6) << path;
    }
  }
}

TEST(TrajectoryIo, ReadsTheRealEurocGroundTruth) {
  const std::string path = std::string(VIO_SHARED_DIR) +
                           "/data/euroc_MH_05_imu_gt/mav0/"
                           "state_groundtruth_estimate0/data.csv";
  const std::vector<StampedState> gt = ReadEurocGroundTruth(path);
  ASSERT_EQ(gt.size(), 22212u);  // 22213 lines, one of them the header
  // First data line: 1403638519492829440,4.460675,-1.680515,0.579614,
  // 0.238261,-0.757610,-0.348629,-0.497711,0.006246,-0.001431,-0.004391,
  // -0.001806,0.020940,0.076870,-0.020544,0.124837,0.061800
  EXPECT_EQ(gt[0].t_ns, 1403638519492829440LL);
  EXPECT_DOUBLE_EQ(gt[0].p_w_b.x(), 4.460675);
  EXPECT_NEAR(gt[0].q_w_b.w(), 0.238261, 1e-5);  // normalised on reading
  EXPECT_NEAR(gt[0].q_w_b.x(), -0.757610, 1e-5);
  EXPECT_DOUBLE_EQ(gt[0].v_w.z(), -0.004391);
  EXPECT_DOUBLE_EQ(gt[0].b_g.x(), -0.001806);  // b_w columns come first
  EXPECT_DOUBLE_EQ(gt[0].b_a.z(), 0.061800);
  EXPECT_EQ(ReadTrajectory(path).size(), gt.size());
}

TEST(TrajectoryIo, ReadsTumSecondsWithoutLosingNanoseconds) {
  const std::string path = WriteFile("seconds.txt",
                                     "# t x y z qx qy qz qw\n"
                                     "1403638519.492829440 1 2 3 0 0 0 1\n"
                                     "1403638519.5 1 2 3 0 0 0 1\n"
                                     "1403638520 1 2 3 0 0 0 1\n");
  const Trajectory t = ReadTum(path);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].t_ns, 1403638519492829440LL);
  EXPECT_EQ(t[1].t_ns, 1403638519500000000LL);
  EXPECT_EQ(t[2].t_ns, 1403638520000000000LL);
}

TEST(TrajectoryIo, ShortLineNamesFileAndLine) {
  const std::string tum = ErrorOf("short.txt",
                                  "0.0 0 0 0 0 0 0 1\n"
                                  "0.1 0 0 0 0 0\n",
                                  ReadTum);
  EXPECT_THAT(tum, HasSubstr("short.txt:2: expected 8 fields, got 6"));
  const std::string csv = ErrorOf("short.csv",
                                  "#header\n"
                                  "1,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n"
                                  "2,0,0,0,1,0,0,0,0,0,0\n",
                                  ReadEurocGroundTruth);
  EXPECT_THAT(csv, HasSubstr("short.csv:3: expected 17 fields, got 11"));
}

TEST(TrajectoryIo, NonNumberNamesTheField) {
  EXPECT_THAT(ErrorOf("nan.txt", "0.0 0 abc 0 0 0 0 1\n", ReadTum),
              HasSubstr("nan.txt:1: field 3 is not a number ('abc')"));
  EXPECT_THAT(ErrorOf("stamp.csv", "12x,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n",
                      ReadEurocGroundTruth),
              HasSubstr("stamp.csv:1: field 1 is not an integer ('12x')"));
  EXPECT_THAT(ErrorOf("stamp.txt", "0.5s 0 0 0 0 0 0 1\n", ReadTum),
              HasSubstr("stamp.txt:1: timestamp is not a number of seconds "
                        "('0.5s')"));
  EXPECT_THAT(ErrorOf("inf.txt", "0.0 0 0 inf 0 0 0 1\n", ReadTum),
              HasSubstr("inf.txt:1: field 4 is not finite ('inf')"));
}

TEST(TrajectoryIo, SignInsideTheFractionIsNotANumber) {
  // "1.-5" must not read as 1 s - 0.5 s.
  EXPECT_THAT(ErrorOf("sign.txt", "1.-5 0 0 0 0 0 0 1\n", ReadTum),
              HasSubstr("sign.txt:1: timestamp is not a number of seconds"));
  EXPECT_THAT(ErrorOf("hex.txt", "0x10 0 0 0 0 0 0 1\n", ReadTum),
              HasSubstr("hex.txt:1: timestamp is not a number of seconds"));
  // Past int64 nanoseconds.
  EXPECT_THAT(ErrorOf("big.txt", "99999999999.5 0 0 0 0 0 0 1\n", ReadTum),
              HasSubstr("big.txt:1: timestamp is out of range"));
}

TEST(TrajectoryIo, NonUnitQuaternionIsAnError) {
  EXPECT_THAT(ErrorOf("quat.txt", "0.0 0 0 0 0 0 0 1.01\n", ReadTum),
              HasSubstr("quat.txt:1: quaternion is not of unit norm (norm "
                        "1.01"));
  EXPECT_THAT(ErrorOf("quat.csv", "1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n",
                      ReadEurocGroundTruth),
              HasSubstr("quat.csv:1: quaternion is not of unit norm (norm 0"));
  // Within 1e-3 it is accepted (and normalised).
  EXPECT_EQ(ErrorOf("quat_ok.txt", "0.0 0 0 0 0 0 0 1.0005\n", ReadTum), "");
}

TEST(TrajectoryIo, StampsThatGoBackAreAnError) {
  EXPECT_THAT(ErrorOf("order.txt",
                      "1.0 0 0 0 0 0 0 1\n"
                      "0.9 0 0 0 0 0 0 1\n",
                      ReadTum),
              HasSubstr("order.txt:2: timestamp 900000000 is before the "
                        "previous one (1000000000)"));
  // The dataset's ground truth must strictly increase.
  EXPECT_THAT(ErrorOf("repeat.csv",
                      "5,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n"
                      "5,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n",
                      ReadEurocGroundTruth),
              HasSubstr("repeat.csv:2: timestamp 5 is not after the previous "
                        "one (5)"));
}

TEST(TrajectoryIo, UnknownFormatSaysWhatItFound) {
  EXPECT_THAT(ErrorOf("unknown.txt", "1 2 3 4 5\n", ReadTrajectory),
              HasSubstr("unknown.txt:1: cannot tell the format: 5 fields (TUM "
                        "has 8, KITTI 12 separated by blanks, a EuRoC CSV 8 "
                        "or more separated by commas, the first an "
                        "integer)"));
  EXPECT_THAT(ErrorOf("empty.txt", "# only a comment\n\n", ReadTrajectory),
              HasSubstr("empty.txt: holds no data line"));
  EXPECT_THAT(ErrorOf("tum9.txt", "0 0 0 0 0 0 0 1 7\n", ReadTum),
              HasSubstr("tum9.txt:1: a TUM line has 8 fields, got 9"));
}

TEST(TrajectoryIo, MissingFileIsAnError) {
  const std::string path = TempPath("does_not_exist.txt");
  std::remove(path.c_str());
  for (auto reader : {+[](const std::string& p) { ReadTrajectory(p); },
                      +[](const std::string& p) { ReadTum(p); },
                      +[](const std::string& p) { ReadEurocGroundTruth(p); }}) {
    try {
      reader(path);
      ADD_FAILURE() << "no error for a missing file";
    } catch (const DatasetError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path + ": cannot open the file"));
    }
  }
}

TEST(TrajectoryIo, UnwritablePathIsAnError) {
  const std::string path = TempPath("no_such_dir/out.txt");
  EXPECT_THROW(WriteTum(path, Trajectory(1)), DatasetError);
  EXPECT_THROW(WriteStateCsv(path, std::vector<StampedState>(1)), DatasetError);
}

}  // namespace
}  // namespace vio
