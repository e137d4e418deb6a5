// Runs the vio_eval program (VIO_EVAL_TOOL) on files written here and checks
// its exit status, its printed figures and its plot.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>
#include <string>

#include "dataset/trajectory_io.h"
#include "test/testing/trajectories.h"

namespace vio {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

struct RunResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

RunResult RunTool(const std::string& args) {
  const std::string command = std::string(VIO_EVAL_TOOL) + " " + args + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), n);
  }
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result;
}

// The number printed on the line that starts with `name ` ("ATE rmse").
double Figure(const std::string& output, const std::string& name) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(name + " ", 0) == 0) {
      return std::stod(line.substr(name.size() + 1));
    }
  }
  ADD_FAILURE() << "no line '" << name << "' in:\n" << output;
  return -1.0;
}

// A file name of this test's own: ctest runs the tests in parallel.
std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "vio_eval_tool_test_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
         name;
}

// Ground truth as a EuRoC-style state CSV (200 poses at 20 Hz); the estimate
// as TUM: the same poses 4 ms late, in a frame scaled by 1/2 and turned, with
// 1 cm of position noise.
struct Files {
  std::string gt = Temp("gt.csv");
  std::string est = Temp("est.txt");
  Files() {
    const Trajectory gt_poses = testing::Lissajous(200);
    std::vector<StampedState> states;
    for (const StampedPose& p : gt_poses) {
      StampedState s;
      s.t_ns = p.t_ns;
      s.p_w_b = p.p_w_b;
      s.q_w_b = p.q_w_b;
      states.push_back(s);
    }
    WriteStateCsv(gt, states);
    std::mt19937 rng(42);
    const testing::Similarity S{testing::Yaw(0.8), {1, 2, 3}, 2.0};
    Trajectory est_poses = testing::AddPositionNoise(
        testing::Transform(S.Inverse(), gt_poses), 0.005, rng);
    for (StampedPose& p : est_poses) p.t_ns += 4000000;
    WriteTum(est, est_poses);
  }
};

TEST(VioEvalTool, PrintsNamedFiguresAndWritesThePlot) {
  const Files files;
  const std::string png = Temp("plot.png");
  std::remove(png.c_str());
  const RunResult r =
      RunTool(files.est + " " + files.gt + " --align sim3 --plot " + png);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(Figure(r.output, "associated poses"), 200.0);
  EXPECT_NEAR(Figure(r.output, "alignment scale"), 2.0, 0.01);
  // 5 mm noise in the estimate's frame is 1 cm after scaling by 2: rmse
  // ~ 1 cm * sqrt(3).
  EXPECT_NEAR(Figure(r.output, "ATE rmse"), 0.01 * std::sqrt(3.0), 0.003);
  EXPECT_THAT(r.output, HasSubstr("\nATE rmse "));
  EXPECT_THAT(r.output, HasSubstr(" m\n"));
  EXPECT_GT(Figure(r.output, "RPE 1m pairs"), 10.0);
  EXPECT_GT(Figure(r.output, "RPE 1m trans rmse"), 0.0);
  const cv::Mat image = cv::imread(png);
  ASSERT_FALSE(image.empty()) << "no readable PNG at " << png;
  EXPECT_EQ(image.cols, 1000);
  EXPECT_EQ(image.rows, 1100);
}

TEST(VioEvalTool, Se3WithoutScaleSeesTheScaleErrorAndNoneSeesTheFrame) {
  const Files files;
  const RunResult se3 = RunTool(files.est + " " + files.gt + " --align se3");
  ASSERT_EQ(se3.status, 0) << se3.output;
  EXPECT_EQ(Figure(se3.output, "alignment scale"), 1.0);
  EXPECT_GT(Figure(se3.output, "ATE rmse"), 0.5);  // half-size loop
  const RunResult none = RunTool(files.est + " " + files.gt + " --align none");
  ASSERT_EQ(none.status, 0) << none.output;
  EXPECT_GT(Figure(none.output, "ATE rmse"), Figure(se3.output, "ATE rmse"));
}

TEST(VioEvalTool, MaxDiffBelowTheOffsetLeavesTooFewAssociations) {
  const Files files;
  const RunResult r = RunTool(files.est + " " + files.gt + " --max-diff 0.003");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: too few associations: 0 pose pairs"));
}

TEST(VioEvalTool, TwoKittiFilesArePairedLineByLine) {
  // The estimate: the ground truth in another frame (turned and moved), as
  // KITTI pose files; se3 alignment must take the frame out exactly.
  const Trajectory gt_poses = testing::Lissajous(120);
  const testing::Similarity S{testing::Yaw(-0.6), {3, -1, 0.5}, 1.0};
  const std::string gt = Temp("gt.kitti"), est = Temp("est.kitti");
  WriteKitti(gt, gt_poses);
  WriteKitti(est, testing::Transform(S, gt_poses));
  const std::string png = Temp("kitti.png");
  RunResult r = RunTool(est + " " + gt + " --align se3 --plot " + png);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("(KITTI)\n"));
  EXPECT_THAT(r.output, HasSubstr("association by line (KITTI)\n"));
  EXPECT_EQ(Figure(r.output, "associated poses"), 120.0);
  // 9 significant digits written: a few metres to ~1e-8 m.
  EXPECT_LT(Figure(r.output, "ATE rmse"), 1e-6);
  EXPECT_FALSE(cv::imread(png).empty());
  // Without alignment the frame change is the error.
  r = RunTool(est + " " + gt + " --align none");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_GT(Figure(r.output, "ATE rmse"), 1.0);

  // evo's kitti mode needs as many poses in both files, and KITTI pairs
  // with KITTI only.
  const std::string shorter = Temp("short.kitti");
  WriteKitti(shorter, Trajectory(gt_poses.begin(), gt_poses.end() - 1));
  r = RunTool(shorter + " " + gt);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: pairing by line needs as many poses "
                                  "in both files: the estimate has 119, the "
                                  "ground truth 120"));
  const std::string tum = Temp("gt.tum");
  WriteTum(tum, gt_poses);
  r = RunTool(est + " " + tum);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: a KITTI pose file has no stamps"));
}

// A TUM ground truth with repeated stamps whose later repeats hold a wrong
// pose (1 m off), and an estimate 2 ms late written as evo writes TUM
// ("%.18e"): evo pairs each estimate with the first pose of the nearest,
// repeated stamp, so the ATE stays at the estimate's own 0; pairing a later
// repeat would cost metres.
TEST(VioEvalTool, RepeatedGroundTruthStampsPairAsEvoPairsThem) {
  const Trajectory truth = testing::Lissajous(100);
  std::ofstream gt(Temp("gt.tum"));
  std::ofstream est(Temp("est.tum"));
  char line[512];
  for (const StampedPose& p : truth) {
    const Eigen::Quaterniond& q = p.q_w_b;
    for (int copy = 0; copy < 2; ++copy) {
      const double x = p.p_w_b.x() + copy;  // the repeat is 1 m off
      std::snprintf(line, sizeof(line),
                    "%lld.%09lld %.9f %.9f %.9f %.9f %.9f "
                    "%.9f %.9f\n",
                    static_cast<long long>(p.t_ns / 1000000000),
                    static_cast<long long>(p.t_ns % 1000000000), x, p.p_w_b.y(),
                    p.p_w_b.z(), q.x(), q.y(), q.z(), q.w());
      gt << line;
    }
    std::snprintf(line, sizeof(line),
                  "%.18e %.18e %.18e %.18e %.18e %.18e %.18e %.18e\n",
                  static_cast<double>(p.t_ns + 2000000) * 1e-9, p.p_w_b.x(),
                  p.p_w_b.y(), p.p_w_b.z(), q.x(), q.y(), q.z(), q.w());
    est << line;
  }
  gt.close();
  est.close();
  const RunResult r =
      RunTool(Temp("est.tum") + " " + Temp("gt.tum") + " --align none");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(Figure(r.output, "ground truth " + Temp("gt.tum") + " poses"),
            200.0);
  EXPECT_EQ(Figure(r.output, "associated poses"), 100.0);
  EXPECT_LT(Figure(r.output, "ATE rmse"), 1e-8);
}

TEST(VioEvalTool, BadInputIsAnErrorWithExitStatusOne) {
  const Files files;
  const std::string missing = Temp("missing.txt");
  std::remove(missing.c_str());
  RunResult r = RunTool(missing + " " + files.gt);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, StartsWith("error: " + missing + ": cannot open"));

  const std::string bad = Temp("bad.txt");
  std::ofstream(bad) << "0.0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n";
  r = RunTool(bad + " " + files.gt);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output,
              StartsWith("error: " + bad + ":2: field 4 is not a number"));

  r = RunTool(files.est + " " + files.gt + " --align affine");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, StartsWith("error: unknown alignment 'affine'"));
  r = RunTool(files.est);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, StartsWith("error: expected EST and GT files"));
  r = RunTool(files.est + " " + files.gt + " --rpe-deltas 1,x");
  EXPECT_EQ(r.status, 1);
  r = RunTool(files.est + " " + files.gt + " --plot " + Temp("no_dir/p.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: " + Temp("no_dir/p.png")));
}

}  // namespace
}  // namespace vio
