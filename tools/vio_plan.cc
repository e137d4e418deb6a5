// vio_plan: the notes' A* (navigation/astar.h) on Moving AI benchmark files,
// or in the place a VIO run mapped (vio_replay's output folder).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset/landmarks_io.h"
#include "dataset/trajectory_io.h"
#include "navigation/astar.h"
#include "navigation/moving_ai.h"
#include "navigation/navigation_error.h"
#include "navigation/navigation_plot.h"
#include "navigation/occupancy_grid.h"
#include "tools/command_line.h"

namespace {

using namespace vio;  // NOLINT(build/namespaces): a tool's main file
namespace fs = std::filesystem;

constexpr char kUsage[] =
    "usage: vio_plan --map M.map --scen S.scen --out R.csv [--four]\n"
    "       vio_plan --replay OUT_DIR [--cell 0.1] [--radius 0.3]\n"
    "                [--start x,y] [--goal x,y] [--band zmin,zmax]\n"
    "                [--min-parallax 3] [--min-points 1] [--out DIR]\n"
    "\n"
    "Benchmark files: solves every scenario of S.scen on M.map (Moving AI\n"
    "format, 8-connected, sqrt(2) diagonals, no corner cutting; --four:\n"
    "4-connected) and writes R.csv: index,length,expansions,microseconds, one\n"
    "row per scenario in file order (length -1 when there is no path). Prints\n"
    "how many lengths differ from the file's optimal lengths by more than\n"
    "1e-4 and exits 1 if any does.\n"
    "\n"
    "Replay: builds an occupancy grid of the ground plane from\n"
    "OUT_DIR/landmarks.csv and OUT_DIR/trajectory.tum (vio_replay's output):\n"
    "landmarks in the height band and seen over at least --min-parallax are\n"
    "obstacles, grown by --radius, the flown path's cells free. Plans from\n"
    "the first pose to the last (or --start / --goal, world metres) and\n"
    "writes DIR/path.csv (x_m,y_m of the path's cell centres) and\n"
    "DIR/plan.png (DIR: --out, default OUT_DIR).\n"
    "\n"
    "  --cell C          cell side [m] (default 0.1)\n"
    "  --radius R        robot radius: obstacles grow by it [m] (default 0.3)\n"
    "  --band zmin,zmax  landmark heights that are obstacles [m] (default:\n"
    "                    the trajectory's height range +- 0.5 m)\n"
    "  --min-parallax A  smallest triangulation angle of a landmark used\n"
    "                    [deg] (default 3; files without angles: all used)\n"
    "  --min-points N    landmarks in a cell to occupy it (default 1)\n";

struct Args {
  std::string map, scen, out, replay;
  bool four = false;
  OccupancyOptions occupancy;
  double min_parallax_deg = 3.0;
  bool have_start = false, have_goal = false;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  bool help = false;
};

Eigen::Vector2d ParsePair(const std::string& flag, const std::string& text) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos) {
    throw std::invalid_argument(flag + " expects two numbers a,b (got '" +
                                text + "')");
  }
  return {ParseNumber<double>(flag, text.substr(0, comma)),
          ParseNumber<double>(flag, text.substr(comma + 1))};
}

Args ParseArgs(int argc, char** argv) {
  Args args;
  CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--help" || a == "-h") {
      args.help = true;
      return args;
    } else if (a == "--map") {
      args.map = line.Value();
    } else if (a == "--scen") {
      args.scen = line.Value();
    } else if (a == "--out") {
      args.out = line.Value();
    } else if (a == "--four") {
      args.four = true;
    } else if (a == "--replay") {
      args.replay = line.Value();
    } else if (a == "--cell") {
      args.occupancy.cell_m = line.Number<double>();
    } else if (a == "--radius") {
      args.occupancy.radius_m = line.Number<double>();
    } else if (a == "--min-points") {
      args.occupancy.min_points = line.Number<int>();
    } else if (a == "--min-parallax") {
      args.min_parallax_deg = line.Number<double>();
    } else if (a == "--band") {
      const Eigen::Vector2d band = ParsePair(a, line.Value());
      args.occupancy.band_min_z_m = band.x();
      args.occupancy.band_max_z_m = band.y();
    } else if (a == "--start") {
      args.start = ParsePair(a, line.Value());
      args.have_start = true;
    } else if (a == "--goal") {
      args.goal = ParsePair(a, line.Value());
      args.have_goal = true;
    } else {
      throw std::invalid_argument("unknown argument " + a + " (see --help)");
    }
  }
  if (args.help) return args;
  const bool files = !args.map.empty() || !args.scen.empty();
  if (files == !args.replay.empty()) {
    throw std::invalid_argument(
        "give either --map, --scen and --out, or --replay\n" +
        std::string(kUsage));
  }
  if (files && (args.map.empty() || args.scen.empty() || args.out.empty())) {
    throw std::invalid_argument("--map, --scen and --out go together");
  }
  args.occupancy.Validate();
  if (!(args.min_parallax_deg >= 0.0)) {
    throw std::invalid_argument("--min-parallax must be >= 0");
  }
  return args;
}

double Microseconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

// Moving AI files: every scenario, in file order.
int SolveScenarios(const Args& args) {
  const Grid grid = ReadMovingAiMap(args.map);
  const std::vector<MovingAiScenario> scenarios =
      ReadMovingAiScenarios(args.scen);
  for (const MovingAiScenario& s : scenarios) CheckScenario(grid, s, args.scen);
  std::printf("map %s: %d x %d, %lld blocked; %zu scenarios in %s; %s\n",
              args.map.c_str(), grid.width(), grid.height(),
              static_cast<long long>(grid.CountBlocked()), scenarios.size(),
              args.scen.c_str(),
              args.four ? "4-connected" : "8-connected, no corner cutting");
  GridPlanner planner(grid,
                      args.four ? Connectivity::kFour : Connectivity::kEight);
  std::ofstream out(args.out);
  if (!out) throw std::runtime_error(args.out + ": cannot open for writing");
  out << "index,length,expansions,microseconds\n";
  constexpr double kTolerance = 1e-4;  // the files print 5 to 8 decimals
  int differing = 0, without_path = 0;
  int64_t expansions = 0;
  double total_us = 0.0;
  char row[128];
  for (size_t i = 0; i < scenarios.size(); ++i) {
    const MovingAiScenario& s = scenarios[i];
    const auto t0 = std::chrono::steady_clock::now();
    const PlanResult r = planner.Plan(s.start, s.goal);
    const double us = Microseconds(std::chrono::steady_clock::now() - t0);
    std::snprintf(row, sizeof(row), "%zu,%.8f,%lld,%.3f\n", i,
                  r.found ? r.length : -1.0,
                  static_cast<long long>(r.expansions), us);
    out << row;
    without_path += r.found ? 0 : 1;
    expansions += r.expansions;
    total_us += us;
    if (std::abs(r.length - s.optimal_length) > kTolerance) {
      if (differing < 10) {
        std::printf("%s:%d: length %.8f, the file says %.8f\n",
                    args.scen.c_str(), s.line, r.length, s.optimal_length);
      }
      ++differing;
    }
  }
  if (!out) throw std::runtime_error(args.out + ": write failed");
  std::printf(
      "solved %zu scenarios (%d without a path): %lld expansions in %.1f ms, "
      "%.2f M expansions/s\n",
      scenarios.size(), without_path, static_cast<long long>(expansions),
      1e-3 * total_us, total_us > 0 ? expansions / total_us : 0.0);
  std::printf("wrote %s\n", args.out.c_str());
  std::printf("lengths differing from the file's (> %g): %d of %zu\n",
              kTolerance, differing, scenarios.size());
  return differing == 0 ? 0 : 1;
}

// A --start / --goal (or a pose) as a free cell; NavigationError naming the
// flag otherwise.
Cell FreeCell(const OccupancyGrid& g, const Eigen::Vector2d& xy,
              const std::string& name) {
  const Cell c = g.ToCell(xy);
  std::ostringstream where;
  where.precision(3);
  where << std::fixed << name << " (" << xy.x() << ", " << xy.y() << ") m";
  if (!g.grid.Contains(c)) {
    where << " is off the grid (x in [" << g.x_min_m << ", "
          << g.x_min_m + g.grid.width() * g.cell_m << "], y in ["
          << g.y_max_m - g.grid.height() * g.cell_m << ", " << g.y_max_m
          << "] m)";
    throw NavigationError(where.str());
  }
  if (g.grid.Blocked(c)) {
    where << " is blocked (an obstacle or within --radius of one)";
    throw NavigationError(where.str());
  }
  return c;
}

int PlanInReplay(const Args& args) {
  const fs::path dir(args.replay);
  const std::string out_dir = args.out.empty() ? args.replay : args.out;
  const Trajectory trajectory =
      ReadTrajectory((dir / "trajectory.tum").string());
  const std::vector<LandmarkRow> rows =
      ReadLandmarksCsv((dir / "landmarks.csv").string());
  std::vector<Eigen::Vector3d> landmarks, flown;
  for (const LandmarkRow& l : rows) {
    if (l.parallax_deg < 0.0 || l.parallax_deg >= args.min_parallax_deg) {
      landmarks.push_back(l.p_w);
    }
  }
  for (const StampedPose& p : trajectory) flown.push_back(p.p_w_b);
  const OccupancyGrid g = BuildOccupancyGrid(landmarks, flown, args.occupancy);
  std::printf(
      "replay %s: %zu poses, %zu landmarks (%zu seen over >= %g deg)\n"
      "grid %d x %d cells of %g m, band z in [%.2f, %.2f] m: %d landmarks "
      "used (%d farther than %g m ignored), %d occupied cells, radius %g m, "
      "%d flown cells freed\n",
      args.replay.c_str(), trajectory.size(), rows.size(), landmarks.size(),
      args.min_parallax_deg, g.grid.width(), g.grid.height(), g.cell_m,
      g.band_min_z_m, g.band_max_z_m, g.landmarks_in_band, g.landmarks_far,
      args.occupancy.max_distance_m, g.occupied_cells, args.occupancy.radius_m,
      g.flown_cells_cleared);
  const Eigen::Vector2d start_xy =
      args.have_start ? args.start : flown.front().head<2>();
  const Eigen::Vector2d goal_xy =
      args.have_goal ? args.goal : flown.back().head<2>();
  const Cell start =
      FreeCell(g, start_xy, args.have_start ? "--start" : "the first pose");
  const Cell goal =
      FreeCell(g, goal_xy, args.have_goal ? "--goal" : "the last pose");

  GridPlanner planner(g.grid);
  const auto t0 = std::chrono::steady_clock::now();
  const PlanResult r = planner.Plan(start, goal);
  const double us = Microseconds(std::chrono::steady_clock::now() - t0);
  std::vector<Eigen::Vector2d> path_xy;
  for (const Cell& c : r.path) path_xy.push_back(g.CellCentre(c));
  fs::create_directories(out_dir);
  const std::string path_csv = (fs::path(out_dir) / "path.csv").string();
  std::ofstream out(path_csv);
  if (!out) throw std::runtime_error(path_csv + ": cannot open for writing");
  out << "x_m,y_m\n";
  char row[64];
  for (const Eigen::Vector2d& p : path_xy) {
    std::snprintf(row, sizeof(row), "%.4f,%.4f\n", p.x(), p.y());
    out << row;
  }
  if (!out) throw std::runtime_error(path_csv + ": write failed");
  std::printf("start (%.2f, %.2f) m, goal (%.2f, %.2f) m, straight %.2f m\n",
              start_xy.x(), start_xy.y(), goal_xy.x(), goal_xy.y(),
              (goal_xy - start_xy).norm());
  if (r.found) {
    std::printf("path %.2f m (%zu cells), %lld expansions, %.0f us\n",
                r.length * g.cell_m, r.path.size(),
                static_cast<long long>(r.expansions), us);
  } else {
    std::printf("no path (%lld expansions, %.0f us)\n",
                static_cast<long long>(r.expansions), us);
  }
  std::vector<Eigen::Vector2d> landmarks_xy, trajectory_xy;
  for (const Eigen::Vector3d& l : landmarks) {
    if (l.z() >= g.band_min_z_m && l.z() <= g.band_max_z_m) {
      landmarks_xy.push_back(l.head<2>());
    }
  }
  for (const Eigen::Vector3d& p : flown) trajectory_xy.push_back(p.head<2>());
  const std::string png = (fs::path(out_dir) / "plan.png").string();
  std::ostringstream title;
  title.precision(3);
  title << "vio_plan: " << args.replay << ", cell " << g.cell_m << " m, radius "
        << args.occupancy.radius_m << " m, ";
  if (r.found) {
    title << "path " << r.length * g.cell_m << " m";
  } else {
    title << "no path";
  }
  WritePlanPlot(png, title.str(), g, landmarks_xy, trajectory_xy, path_xy,
                start_xy, goal_xy);
  std::printf("wrote %s and %s\n", path_csv.c_str(), png.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::printf("%s", kUsage);
      return 0;
    }
    return args.replay.empty() ? SolveScenarios(args) : PlanInReplay(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
