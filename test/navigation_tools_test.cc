// Runs the vio_filter and vio_plan programs (VIO_FILTER_TOOL, VIO_PLAN_TOOL)
// on files written here: exit status, printed figures, written files, and
// bad input as a file:line error with status 1.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "dataset/landmarks_io.h"
#include "dataset/sim_trajectory.h"
#include "dataset/trajectory_io.h"
#include "navigation/astar.h"
#include "navigation/grid_generator.h"
#include "navigation/moving_ai.h"
#include "testing/grid_search_reference.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

using ::testing::HasSubstr;
using testing::TempFolder;

struct RunResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

RunResult RunTool(const std::string& tool, const std::string& args) {
  const std::string command = tool + " " + args + " 2>&1";
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

// The number after `label` in the output.
double NumberAfter(const std::string& output, const std::string& label) {
  const size_t at = output.find(label);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no '" << label << "' in:\n" << output;
    return -1.0;
  }
  return std::stod(output.substr(at + label.size()));
}

int CountLines(const std::string& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// A generated maze with its scenarios; lengths from the test's own Dijkstra.
void WriteMaze(const TempFolder& dir, double length_offset_of_first) {
  const Grid maze = MazeGrid(61, 41, 3);
  WriteMovingAiMap(dir.Path("maze.map"), maze);
  std::vector<MovingAiScenario> scenarios;
  for (const auto& [s, g] : RandomQueries(maze, 30, 4)) {
    MovingAiScenario sc;
    sc.map = "maze.map";
    sc.map_width = maze.width();
    sc.map_height = maze.height();
    sc.start = s;
    sc.goal = g;
    sc.optimal_length = testing::ReferenceDijkstra(maze, s, g, true).length;
    scenarios.push_back(sc);
  }
  scenarios[0].optimal_length += length_offset_of_first;
  WriteMovingAiScenarios(dir.Path("maze.map.scen"), scenarios);
}

TEST(VioPlanTool, SolvesAScenarioFileToItsLengths) {
  TempFolder dir;
  WriteMaze(dir, 0.0);
  const RunResult r =
      RunTool(VIO_PLAN_TOOL, "--map " + dir.Path("maze.map") + " --scen " +
                                 dir.Path("maze.map.scen") + " --out " +
                                 dir.Path("r.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("lengths differing from the file's "
                                  "(> 0.0001): 0 of 30"));
  EXPECT_EQ(CountLines(dir.Path("r.csv")), 31);
  std::ifstream csv(dir.Path("r.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "index,length,expansions,microseconds");
}

TEST(VioPlanTool, AWrongLengthInTheFileIsStatusOne) {
  TempFolder dir;
  WriteMaze(dir, 1.0);
  const RunResult r =
      RunTool(VIO_PLAN_TOOL, "--map " + dir.Path("maze.map") + " --scen " +
                                 dir.Path("maze.map.scen") + " --out " +
                                 dir.Path("r.csv"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("maze.map.scen:2: length"));
  EXPECT_THAT(r.output, HasSubstr(": 1 of 30"));
}

TEST(VioPlanTool, BadFilesAreFileLineErrors) {
  TempFolder dir;
  WriteMaze(dir, 0.0);
  dir.Write("bad.map", "type octile\nheight 2\nwidth 2\nmap\n..\n.?\n");
  RunResult r =
      RunTool(VIO_PLAN_TOOL, "--map " + dir.Path("bad.map") + " --scen " +
                                 dir.Path("maze.map.scen") + " --out " +
                                 dir.Path("r.csv"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: "));
  EXPECT_THAT(r.output, HasSubstr("bad.map:6: column 1: unknown terrain '?'"));
  // The maze's (0, 0) is a wall.
  dir.Write("blocked.scen", "version 1\n0\tmaze.map\t61\t41\t0\t0\t1\t1\t1\n");
  r = RunTool(VIO_PLAN_TOOL, "--map " + dir.Path("maze.map") + " --scen " +
                                 dir.Path("blocked.scen") + " --out " +
                                 dir.Path("r.csv"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("blocked.scen:2: start (0, 0) is blocked"));
}

// A replay folder: a flight around a wall of landmarks (x = 2 m, y from -1
// to 3 m), as vio_replay would write it.
void WriteReplay(const TempFolder& dir) {
  Trajectory flight;
  const Eigen::Vector2d corners[] = {{0, 0}, {0, 4}, {4, 4}, {4, 0}};
  int64_t t = 1000000000;
  for (int leg = 0; leg < 3; ++leg) {
    for (int k = 0; k < 40; ++k, t += 50000000) {
      const Eigen::Vector2d p =
          corners[leg] + (corners[leg + 1] - corners[leg]) * (k / 40.0);
      flight.push_back(
          {t, {p.x(), p.y(), 1.0}, Eigen::Quaterniond::Identity()});
    }
  }
  flight.push_back({t, {4.0, 0.0, 1.0}, Eigen::Quaterniond::Identity()});
  WriteTum(dir.Path("out/trajectory.tum"), flight);
  std::vector<LandmarkRow> wall;
  for (int i = 0; i <= 40; ++i) {
    wall.push_back({{2.0, -1.0 + 0.1 * i, 1.0}, 10.0});
    wall.push_back({{1.0, -1.0 + 0.1 * i, 1.0}, 0.5});  // too narrow an angle
  }
  WriteLandmarksCsv(dir.Path("out/landmarks.csv"), wall);
}

TEST(VioPlanTool, PlansAroundTheMappedWallOfAReplay) {
  TempFolder dir;
  std::filesystem::create_directories(dir.Path("out"));
  WriteReplay(dir);
  const RunResult r =
      RunTool(VIO_PLAN_TOOL, "--replay " + dir.Path("out") + " --radius 0.2");
  EXPECT_EQ(r.status, 0) << r.output;
  // From (0, 0) to (4, 0) around the south end at y = -1.2 m: 2 hypot(2,
  // 1.2) = 4.66 m at least; the narrow-angle landmarks at x = 1 are ignored.
  EXPECT_THAT(r.output, HasSubstr("(41 seen over >= 3 deg)"));
  const double length = NumberAfter(r.output, "path ");
  EXPECT_GT(length, 4.6);
  EXPECT_LT(length, 5.6);
  EXPECT_GT(CountLines(dir.Path("out/path.csv")), 40);
  EXPECT_TRUE(std::filesystem::exists(dir.Path("out/plan.png")));
}

TEST(VioPlanTool, AStartOffTheGridOrBlockedIsAnError) {
  TempFolder dir;
  std::filesystem::create_directories(dir.Path("out"));
  WriteReplay(dir);
  RunResult r =
      RunTool(VIO_PLAN_TOOL, "--replay " + dir.Path("out") + " --start 50,0");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: --start (50.000, 0.000) m is off "
                                  "the grid"));
  r = RunTool(VIO_PLAN_TOOL, "--replay " + dir.Path("out") + " --goal 2,1");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("error: --goal (2.000, 1.000) m is blocked"));
}

// The default simulated flight at 20 Hz with 2 cm of white position noise
// and 0.02 rad of heading noise.
void WriteNoisyFlight(const TempFolder& dir) {
  const SimTrajectory truth{SimMotionOptions()};
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.02), yaw_noise(0.0, 0.02);
  Trajectory measured, exact;
  for (int i = 0; i < 800; ++i) {
    const int64_t t = 1000000000 + int64_t{i} * 50000000;
    const SimState s = truth.At(0.05 * i);
    // Heading noise of 0.02 rad, vio_filter's default --yaw-noise.
    const Eigen::Quaterniond turn(
        Eigen::AngleAxisd(yaw_noise(rng), Eigen::Vector3d::UnitZ()));
    measured.push_back(
        {t, s.p_w_b + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)),
         turn * s.q_w_b});
  }
  for (int i = 0; i < 8000; ++i) {  // 200 Hz truth
    const SimState s = truth.At(0.005 * i);
    exact.push_back({1000000000 + int64_t{i} * 5000000, s.p_w_b, s.q_w_b});
  }
  WriteTum(dir.Path("in.tum"), measured);
  WriteTum(dir.Path("gt.tum"), exact);
}

TEST(VioFilterTool, PredictionBeatsHoldingOnASimulatedFlight) {
  TempFolder dir;
  WriteNoisyFlight(dir);
  const RunResult r = RunTool(
      VIO_FILTER_TOOL, dir.Path("in.tum") + " --out " + dir.Path("out.tum") +
                           " --position-noise 0.02 --accel-noise 1"
                           " --predict-ms 100 --ground-truth " +
                           dir.Path("gt.tum"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(CountLines(dir.Path("out.tum")), 801);  // header + poses
  const Trajectory out = ReadTum(dir.Path("out.tum"));
  EXPECT_EQ(out.front().t_ns, 1000000000 + 100000000);  // stamped t + D
  EXPECT_LT(NumberAfter(r.output, "(ratio "), 0.5) << r.output;
  // White noise of the stated sigma: the NIS is about its 4 degrees of
  // freedom.
  EXPECT_NEAR(NumberAfter(r.output, "NIS mean "), 4.0, 1.0);
  EXPECT_TRUE(std::filesystem::exists(dir.Path("out.png")));
}

TEST(VioFilterTool, EmptyOrUnsortedTrajectoriesAreFileLineErrors) {
  TempFolder dir;
  dir.Write("unsorted.tum",
            "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n1.5 0 0 0 0 0 0 1\n");
  RunResult r =
      RunTool(VIO_FILTER_TOOL, dir.Path("unsorted.tum") + " --out " +
                                   dir.Path("o.tum") +
                                   " --position-noise 0.02 --accel-noise 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("unsorted.tum:3: timestamp"));
  dir.Write("empty.tum", "# nothing\n");
  r = RunTool(VIO_FILTER_TOOL, dir.Path("empty.tum") + " --out " +
                                   dir.Path("o.tum") +
                                   " --position-noise 0.02 --accel-noise 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("empty.tum: holds no data line"));
  r = RunTool(VIO_FILTER_TOOL, dir.Path("empty.tum") + " --out o.tum");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("--position-noise and --accel-noise are "
                                  "required"));
}

}  // namespace
}  // namespace vio
