// The occupancy grid from landmarks: the height band, the cell count
// threshold, the inflation by the robot's radius, the flown cells freed, and
// a plan through it around a wall.

#include "navigation/occupancy_grid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "navigation/astar.h"

namespace vio {
namespace {

// A wall of landmarks along x = 2 m from y = -1 to y = 3 m (10 cm apart) at
// heights 0, 0.9, 1.1 and 2 m, a floor under it at z = -1 m, and a trajectory
// that flies from (0, 0) to (0, 2) at z = 1 m, west of the wall.
struct Scene {
  static double Y(int i) { return -1.0 + 0.1 * i; }  // wall landmark rows [m]
  std::vector<Eigen::Vector3d> landmarks;
  std::vector<Eigen::Vector3d> trajectory;
  Scene() {
    for (int i = 0; i <= 40; ++i) {
      for (double z : {0.0, 0.9, 1.1, 2.0})
        landmarks.emplace_back(2.0, Y(i), z);
      landmarks.emplace_back(0.5, Y(i), -1.0);  // floor: below the band
    }
    for (int i = 0; i <= 40; ++i) trajectory.emplace_back(0.0, 0.05 * i, 1.0);
  }
};

TEST(OccupancyGrid, CellsAndWorldPointsMapBothWays) {
  const Scene scene;
  const OccupancyGrid g =
      BuildOccupancyGrid(scene.landmarks, scene.trajectory, OccupancyOptions());
  const Cell c{7, 11};
  EXPECT_EQ(g.ToCell(g.CellCentre(c)), c);
  // Up in the world is up in the grid: a larger y is a smaller row.
  EXPECT_LT(g.ToCell({0.0, 2.0}).y, g.ToCell({0.0, 0.0}).y);
  EXPECT_LT(g.ToCell({0.0, 0.0}).x, g.ToCell({2.0, 0.0}).x);
}

TEST(OccupancyGrid, TheBandKeepsTheWallAndDropsTheFloor) {
  const Scene scene;
  const OccupancyGrid g =
      BuildOccupancyGrid(scene.landmarks, scene.trajectory, OccupancyOptions());
  // Band: the trajectory's z (1 m) +- 0.5 m: the wall's 0.9 and 1.1 m rows.
  EXPECT_DOUBLE_EQ(g.band_min_z_m, 0.5);
  EXPECT_DOUBLE_EQ(g.band_max_z_m, 1.5);
  EXPECT_EQ(g.landmarks_in_band, 2 * 41);
  for (int i = 0; i <= 40; ++i) {
    EXPECT_TRUE(g.Occupied(g.ToCell({2.0, Scene::Y(i)}))) << "wall " << i;
    EXPECT_FALSE(g.Occupied(g.ToCell({0.5, Scene::Y(i)}))) << "floor " << i;
  }
}

TEST(OccupancyGrid, ObstaclesGrowByTheRadius) {
  const Scene scene;
  OccupancyOptions o;
  o.radius_m = 0.3;
  const OccupancyGrid g =
      BuildOccupancyGrid(scene.landmarks, scene.trajectory, o);
  // The wall's cells span x in [2.0, 2.1) or so; 0.3 m out is blocked, 0.45 m
  // is free.
  const Cell wall = g.ToCell({2.0, Scene::Y(20)});
  ASSERT_TRUE(g.Occupied(wall));
  const double wall_x = g.CellCentre(wall).x();
  EXPECT_TRUE(g.grid.Blocked(g.ToCell({wall_x - 0.3, 1.0})));
  EXPECT_TRUE(g.grid.Blocked(g.ToCell({wall_x + 0.3, 1.0})));
  EXPECT_FALSE(g.grid.Blocked(g.ToCell({wall_x - 0.45, 1.0})));
  EXPECT_FALSE(g.grid.Blocked(g.ToCell({wall_x + 0.45, 1.0})));
}

TEST(OccupancyGrid, MinPointsIgnoresLoneLandmarks) {
  Scene scene;
  scene.landmarks.emplace_back(-1.0, 1.0, 1.0);  // a stray point
  OccupancyOptions o;
  o.min_points = 2;
  const OccupancyGrid g =
      BuildOccupancyGrid(scene.landmarks, scene.trajectory, o);
  EXPECT_FALSE(g.Occupied(g.ToCell({-1.0, 1.0})));
  EXPECT_TRUE(g.Occupied(g.ToCell({2.0, Scene::Y(20)})));  // two per cell
  o.min_points = 1;
  EXPECT_TRUE(BuildOccupancyGrid(scene.landmarks, scene.trajectory, o)
                  .Occupied(g.ToCell({-1.0, 1.0})));
}

TEST(OccupancyGrid, TheFlownPathIsFreeEvenInsideTheInflation) {
  Scene scene;
  // A trajectory that brushes the wall: its last poses at x = 1.8 m.
  scene.trajectory.emplace_back(1.8, 2.0, 1.0);
  OccupancyOptions o;
  o.radius_m = 0.3;
  const OccupancyGrid g =
      BuildOccupancyGrid(scene.landmarks, scene.trajectory, o);
  EXPECT_GT(g.flown_cells_cleared, 0);
  for (const Eigen::Vector3d& p : scene.trajectory) {
    EXPECT_FALSE(g.grid.Blocked(g.ToCell(p.head<2>())));
  }
}

// The robot flew around the wall's north end; a plan from one side to the
// other must go around one of its ends, never through the inflated wall.
TEST(OccupancyGrid, APlanGoesAroundTheWall) {
  const Scene scene;
  const std::vector<Eigen::Vector3d> flown = {
      {0.0, 0.0, 1.0}, {0.0, 4.0, 1.0}, {4.0, 4.0, 1.0}, {4.0, 0.0, 1.0}};
  OccupancyOptions o;
  o.radius_m = 0.2;
  const OccupancyGrid g = BuildOccupancyGrid(scene.landmarks, flown, o);
  GridPlanner planner(g.grid);
  const PlanResult r = planner.Plan(g.ToCell({0.0, 0.0}), g.ToCell({4.0, 0.0}));
  ASSERT_TRUE(r.found);
  // Around the south end at y = -1 - 0.2 m: at least 2 hypot(2, 1.2) =
  // 4.66 m (the north end is farther).
  EXPECT_GT(r.length * g.cell_m, 4.6);
  for (const Cell& c : r.path) {
    const Eigen::Vector2d p = g.CellCentre(c);
    EXPECT_FALSE(std::abs(p.x() - 2.0) < 0.2 && p.y() > -1.1 && p.y() < 3.1)
        << "through the wall at " << p.transpose();
  }
}

TEST(OccupancyGrid, RejectsBadOptionsAndHugeGrids) {
  const Scene scene;
  OccupancyOptions o;
  o.cell_m = 0.0;
  EXPECT_THROW(BuildOccupancyGrid(scene.landmarks, scene.trajectory, o),
               std::invalid_argument);
  o = OccupancyOptions();
  o.cell_m = 0.001;  // 4 m of wall: 4000+ cells a side
  o.max_cells_per_side = 1000;
  EXPECT_THROW(BuildOccupancyGrid(scene.landmarks, scene.trajectory, o),
               std::invalid_argument);
  EXPECT_THROW(BuildOccupancyGrid(scene.landmarks, {}, OccupancyOptions()),
               std::invalid_argument);
}

}  // namespace
}  // namespace vio
