// Every trajectory file evo reads, read by dataset/trajectory_io.h: numpy's
// scientific stamps, comments and blank lines anywhere, a byte-order mark,
// repeated stamps, pose-only EuRoC CSVs and KITTI pose files. The real files
// are the EuRoC excerpts of ../shared/data, rewritten as each tool writes them.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dataset/csv.h"
#include "dataset/trajectory_io.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using ::testing::HasSubstr;
using testing::TempFolder;

const std::string kMh05 = std::string(VIO_SHARED_DIR) +
                          "/data/euroc_MH_05_imu_gt/mav0/"
                          "state_groundtruth_estimate0/data.csv";

// The first `count` poses of MH_05's real ground truth (200 Hz).
Trajectory RealGroundTruth(size_t count) {
  Trajectory poses;
  for (const StampedState& s : ReadEurocGroundTruth(kMh05)) {
    if (poses.size() == count) break;
    poses.push_back(PoseOf(s));
  }
  return poses;
}

// One TUM line as evo writes it: numpy's savetxt, "%.18e" for every value,
// the stamp a double number of seconds.
std::string NumpyTumLine(const StampedPose& p) {
  char line[512];
  const Eigen::Quaterniond& q = p.q_w_b;
  std::snprintf(line, sizeof(line),
                "%.18e %.18e %.18e %.18e %.18e %.18e %.18e %.18e\n",
                static_cast<double>(p.t_ns) * 1e-9, p.p_w_b.x(), p.p_w_b.y(),
                p.p_w_b.z(), q.x(), q.y(), q.z(), q.w());
  return line;
}

// One KITTI line as KITTI's own files hold it: "%e", 7 significant digits.
std::string KittiLine(const StampedPose& p) {
  const Eigen::Matrix3d R = p.q_w_b.toRotationMatrix();
  std::string line;
  char value[32];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      std::snprintf(value, sizeof(value), "%e", c == 3 ? p.p_w_b(r) : R(r, c));
      line += value;
      line += (r == 2 && c == 3) ? "\n" : " ";
    }
  }
  return line;
}

std::string ErrorOf(const std::string& path,
                    Trajectory (*reader)(const std::string&)) {
  try {
    reader(path);
  } catch (const DatasetError& e) {
    return e.what();
  }
  return "";
}

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

TEST(TrajectoryFormats, NumpyScientificTumReadsLikeTheEurocCsvItCameFrom) {
  const Trajectory truth = RealGroundTruth(2000);
  TempFolder folder;
  std::string text;
  for (const StampedPose& p : truth) text += NumpyTumLine(p);
  folder.Write("evo.tum", text);
  const TrajectoryFile file = ReadTrajectoryFile(folder.Path("evo.tum"));
  EXPECT_EQ(file.format, TrajectoryFormat::kTum);
  ASSERT_EQ(file.poses.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    // The stamp went through doubles twice (ns, then seconds: 128 + 119 ns
    // of rounding at most, and 1e-9 is not exact either); the digits
    // written are read back to the nanosecond.
    ASSERT_LE(std::llabs(file.poses[i].t_ns - truth[i].t_ns), 300) << i;
    ASSERT_LT((file.poses[i].p_w_b - truth[i].p_w_b).norm(), 1e-15) << i;
    ASSERT_LT(AngleBetween(file.poses[i].q_w_b, truth[i].q_w_b), 1e-12) << i;
  }
}

TEST(TrajectoryFormats, RealTumGroundTruthReads) {
  // MH_01's ground truth as OpenVINS publishes it: 5 decimals, a comment.
  const std::string path = std::string(VIO_SHARED_DIR) +
                           "/data/euroc_MH_01_moving_6s/mav0/ground_truth.tum";
  const TrajectoryFile file = ReadTrajectoryFile(path);
  EXPECT_EQ(file.format, TrajectoryFormat::kTum);
  ASSERT_GT(file.poses.size(), 1000u);
  EXPECT_EQ(file.poses[0].t_ns, 1403636584263560000LL);
  EXPECT_DOUBLE_EQ(file.poses[0].p_w_b.x(), 4.709279);
  EXPECT_NEAR(file.poses[0].q_w_b.w(), 0.525862, 1e-6);
}

TEST(TrajectoryFormats, CommentAndBlankLinesAnywhereAreSkipped) {
  TempFolder folder;
  folder.Write("commented.txt",
               "# header\r\n"
               "\r\n"
               "1.0 1 2 3 0 0 0 1\r\n"
               "   # an indented comment between poses\n"
               " \t \n"
               "2.0 4 5 6 0 0 0 1\n"
               "\n"
               "# and one at the end\n"
               "\n");
  const Trajectory t = ReadTum(folder.Path("commented.txt"));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].t_ns, 2000000000LL);
  EXPECT_EQ(t[1].p_w_b, Eigen::Vector3d(4, 5, 6));
  // Skipped lines still count: an error names the file's own line number.
  folder.Write("late_error.txt",
               "# header\n\n1.0 1 2 3 0 0 0 1\n# note\n\n2.0 4 5 x 0 0 0 1\n");
  EXPECT_THAT(ErrorOf(folder.Path("late_error.txt"), ReadTum),
              HasSubstr("late_error.txt:6: field 4 is not a number ('x')"));
}

TEST(TrajectoryFormats, ByteOrderMarkAtTheStartIsSkipped) {
  TempFolder folder;
  folder.Write("bom.tum",
               "\xEF\xBB\xBF"
               "1.0 1 2 3 0 0 0 1\n");
  folder.Write("bom.csv",
               "\xEF\xBB\xBF#timestamp,x,y,z,qw,qx,qy,qz\n"
               "1000,1,2,3,1,0,0,0\n");
  EXPECT_EQ(ReadTrajectory(folder.Path("bom.tum")).size(), 1u);
  EXPECT_EQ(ReadTrajectory(folder.Path("bom.csv")).size(), 1u);
  // Only at the start: elsewhere it is a bad field.
  folder.Write("bom_late.tum",
               "1.0 1 2 3 0 0 0 1\n\xEF\xBB\xBF"
               "2.0 1 2 3 0 0 0 1\n");
  EXPECT_THAT(ErrorOf(folder.Path("bom_late.tum"), ReadTum),
              HasSubstr("bom_late.tum:2: timestamp is not a number"));
}

TEST(TrajectoryFormats, RepeatedStampsAreKeptInFileOrder) {
  TempFolder folder;
  folder.Write("repeat.tum",
               "1305031102.1758 1 0 0 0 0 0 1\n"
               "1305031102.1758 2 0 0 0 0 0 1\n"
               "1305031102.1858 3 0 0 0 0 0 1\n");
  const Trajectory t = ReadTrajectory(folder.Path("repeat.tum"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].t_ns, t[1].t_ns);
  EXPECT_EQ(t[0].p_w_b.x(), 1.0);
  EXPECT_EQ(t[1].p_w_b.x(), 2.0);
  folder.Write("repeat.csv",
               "5,1,0,0,1,0,0,0\n5,2,0,0,1,0,0,0\n6,3,0,0,1,0,0,0\n");
  EXPECT_EQ(ReadTrajectory(folder.Path("repeat.csv")).size(), 3u);
  // Going back stays an error.
  folder.Write("back.tum", "2.0 0 0 0 0 0 0 1\n1.5 0 0 0 0 0 0 1\n");
  EXPECT_THAT(ErrorOf(folder.Path("back.tum"), ReadTrajectory),
              HasSubstr("back.tum:2: timestamp 1500000000 is before the "
                        "previous one (2000000000)"));
  // The dataset's ground truth (interpolated in time) must strictly increase.
  folder.Write("gt.csv",
               "5,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n"
               "5,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n");
  EXPECT_THROW(ReadEurocGroundTruth(folder.Path("gt.csv")), DatasetError);
}

TEST(TrajectoryFormats, PoseOnlyEurocCsvReadsWithItsQuaternionOrder) {
  TempFolder folder;
  // evo's euroc mode reads 8 or more columns: t[ns], p, q(w, x, y, z).
  folder.Write("poses.csv",
               "#timestamp [ns],x,y,z,qw,qx,qy,qz\n"
               "1403636580838555648,1,2,3,0.7071067811865476,0.7071067811865476"
               ",0,0\n");
  const TrajectoryFile file = ReadTrajectoryFile(folder.Path("poses.csv"));
  EXPECT_EQ(file.format, TrajectoryFormat::kEuroc);
  ASSERT_EQ(file.poses.size(), 1u);
  EXPECT_EQ(file.poses[0].t_ns, 1403636580838555648LL);
  EXPECT_NEAR(file.poses[0].q_w_b.x(), 0.7071067811865476, 1e-15);
  EXPECT_NEAR(file.poses[0].q_w_b.w(), 0.7071067811865476, 1e-15);
  // Every line as long as the first, every column a number.
  folder.Write("ragged.csv", "1,1,2,3,1,0,0,0,9\n2,1,2,3,1,0,0,0\n");
  EXPECT_THAT(ErrorOf(folder.Path("ragged.csv"), ReadTrajectory),
              HasSubstr("ragged.csv:2: expected 9 fields, got 8"));
  folder.Write("extra.csv", "1,1,2,3,1,0,0,0,abc\n");
  EXPECT_THAT(ErrorOf(folder.Path("extra.csv"), ReadTrajectory),
              HasSubstr("extra.csv:1: field 9 is not a number ('abc')"));
}

TEST(TrajectoryFormats, KittiPoseFilesReadAsUnstampedPoses) {
  const Trajectory truth = RealGroundTruth(400);
  TempFolder folder;
  std::string text;
  for (const StampedPose& p : truth) text += KittiLine(p);
  folder.Write("kitti.txt", text);
  const TrajectoryFile file = ReadTrajectoryFile(folder.Path("kitti.txt"));
  EXPECT_EQ(file.format, TrajectoryFormat::kKitti);
  EXPECT_FALSE(file.stamped());
  ASSERT_EQ(file.poses.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_EQ(file.poses[i].t_ns, static_cast<int64_t>(i) * 1000000000LL);
    // "%e" keeps 7 significant digits: 5 m to 5e-6 m, a rotation to ~1e-6.
    ASSERT_LT((file.poses[i].p_w_b - truth[i].p_w_b).norm(), 1e-5) << i;
    ASSERT_LT(AngleBetween(file.poses[i].q_w_b, truth[i].q_w_b), 3e-6) << i;
  }
  // The writer's file reads back the same way.
  WriteKitti(folder.Path("written.txt"), truth);
  const Trajectory written = ReadKitti(folder.Path("written.txt"));
  ASSERT_EQ(written.size(), truth.size());
  EXPECT_LT((written.back().p_w_b - truth.back().p_w_b).norm(), 1e-7);
  // Callers that need stamps are told why they get none.
  EXPECT_THAT(ErrorOf(folder.Path("kitti.txt"), ReadTrajectory),
              HasSubstr("kitti.txt: a KITTI pose file has no stamps"));
}

TEST(TrajectoryFormats, KittiLineThatIsNoPoseIsAnError) {
  TempFolder folder;
  folder.Write("scaled.txt", "2 0 0 1 0 1 0 2 0 0 1 3\n");
  EXPECT_THAT(ErrorOf(folder.Path("scaled.txt"), ReadKitti),
              HasSubstr("scaled.txt:1: the 3x3 block is not a rotation"));
  folder.Write("mirror.txt", "-1 0 0 1 0 1 0 2 0 0 1 3\n");
  EXPECT_THAT(ErrorOf(folder.Path("mirror.txt"), ReadKitti),
              HasSubstr("mirror.txt:1: the 3x3 block is not a rotation"));
  folder.Write("short.txt", "1 0 0 1 0 1 0 2 0 0 1 3\n1 0 0 1 0 1 0 2 0 0 1\n");
  EXPECT_THAT(ErrorOf(folder.Path("short.txt"), ReadKitti),
              HasSubstr("short.txt:2: expected 12 fields, got 11"));
}

TEST(TrajectoryFormats, UnknownLayoutSaysWhatItFound) {
  TempFolder folder;
  folder.Write("five.txt", "1 2 3 4 5\n");
  EXPECT_THAT(ErrorOf(folder.Path("five.txt"), ReadTrajectory),
              HasSubstr("five.txt:1: cannot tell the format: 5 fields (TUM "
                        "has 8, KITTI 12"));
  // Twelve comma-separated values with a decimal first field: no format.
  folder.Write("twelve.csv", "1.5,0,0,0,0,0,0,0,0,0,0,0\n");
  EXPECT_THAT(ErrorOf(folder.Path("twelve.csv"), ReadTrajectory),
              HasSubstr("twelve.csv:1: cannot tell the format: 12 "
                        "comma-separated fields"));
}

}  // namespace
}  // namespace vio
