// A* (navigation/astar.h) against a Dijkstra written apart (test/testing/
// grid_search_reference.h) on thousands of random grids, on hand-made maps for
// 4- and 8-connectivity and corner cutting, and on one map per defect of the
// notes' Algorithm 1, each shown to fool the notes' version as written.

#include "navigation/astar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "navigation/grid_generator.h"
#include "testing/grid_search_reference.h"

namespace vio {
namespace {

using testing::GridFromRows;
using testing::NotesAStar;
using testing::NotesDefects;
using testing::ReferenceDijkstra;

// The path is a chain of legal moves from start to goal whose costs add up
// to the reported length.
void ExpectValidPath(const Grid& grid, const PlanResult& r, Cell start,
                     Cell goal, bool eight) {
  ASSERT_FALSE(r.path.empty());
  EXPECT_EQ(r.path.front(), start);
  EXPECT_EQ(r.path.back(), goal);
  double length = 0.0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    bool legal = false;
    for (const auto& [n, cost] : testing::Moves(grid, r.path[i - 1], eight)) {
      if (n == r.path[i]) {
        legal = true;
        length += cost;
      }
    }
    ASSERT_TRUE(legal) << "step " << i << " is not a legal move";
  }
  EXPECT_NEAR(length, r.length, 1e-9);
}

void CompareOnRandomGrids(Connectivity connectivity, int grids) {
  const bool eight = connectivity == Connectivity::kEight;
  std::mt19937 rng(eight ? 8 : 4);
  int with_path = 0;
  for (int i = 0; i < grids; ++i) {
    const int w = 2 + static_cast<int>(rng() % 39);
    const int h = 2 + static_cast<int>(rng() % 39);
    const double fraction = 0.45 * (rng() % 1000) / 1000.0;
    Grid grid = RandomGrid(w, h, fraction, rng());
    const Cell start{static_cast<int>(rng() % w), static_cast<int>(rng() % h)};
    const Cell goal{static_cast<int>(rng() % w), static_cast<int>(rng() % h)};
    grid.SetBlocked(start, false);
    grid.SetBlocked(goal, false);
    const testing::ReferenceResult ref =
        ReferenceDijkstra(grid, start, goal, eight);
    GridPlanner planner(grid, connectivity);
    const PlanResult astar = planner.Plan(start, goal, SearchMode::kAStar);
    const PlanResult dijkstra =
        planner.Plan(start, goal, SearchMode::kDijkstra);
    ASSERT_EQ(astar.found, ref.found) << "grid " << i;
    ASSERT_EQ(dijkstra.found, ref.found) << "grid " << i;
    if (!ref.found) {
      EXPECT_EQ(astar.length, -1.0);
      EXPECT_TRUE(astar.path.empty());
      continue;
    }
    ++with_path;
    ASSERT_NEAR(astar.length, ref.length, 1e-9) << "grid " << i;
    ASSERT_NEAR(dijkstra.length, ref.length, 1e-9) << "grid " << i;
    ASSERT_LE(astar.expansions, ref.expansions) << "grid " << i;
    ASSERT_LE(astar.expansions, dijkstra.expansions) << "grid " << i;
    ExpectValidPath(grid, astar, start, goal, eight);
    ExpectValidPath(grid, dijkstra, start, goal, eight);
  }
  EXPECT_GT(with_path, grids / 2);  // most queries have a path to compare
}

TEST(AStar, EqualsDijkstraOnRandomGridsEightConnected) {
  CompareOnRandomGrids(Connectivity::kEight, 3000);
}

TEST(AStar, EqualsDijkstraOnRandomGridsFourConnected) {
  CompareOnRandomGrids(Connectivity::kFour, 3000);
}

// The fixed-point step costs order paths as their lengths do (astar.cc:
// FixedPointStepCosts), so the least-cost path A* returns is a shortest one.
// Two simple paths of a grid differ by Δa straight and Δb diagonal steps,
// |Δb| <= cells, and in length by Δa + Δb sqrt(2). The hardest pairs are, for
// each Δb, the Δa = -floor(Δb sqrt(2)) and -ceil(Δb sqrt(2)) (the convergents
// 99 - 70 sqrt(2), 577 - 408 sqrt(2), ... among them): for all of them the
// cost difference Δa S + Δb D must have the sign of the length difference,
// which is decided exactly by comparing Δa² with 2 Δb². Grids of 40 x 40 (the
// random grids above), 512 x 512 (the benchmark's) and 1024 x 1024 (2^20
// cells, the largest the bound covers).
TEST(AStar, FixedPointCostsOrderPathsAsTheirLengths) {
  for (const auto& [w, h] :
       std::vector<std::pair<int, int>>{{40, 40}, {512, 512}, {1024, 1024}}) {
    const StepCosts c = FixedPointStepCosts(w, h);
    const int64_t cells = int64_t{w} * h;
    const auto unit = static_cast<int64_t>(c.unit);
    const auto diagonal = static_cast<int64_t>(c.diagonal);
    // No f overflows: g <= D cells, h <= D (w + h).
    ASSERT_LT(static_cast<double>(c.diagonal) * (cells + w + h), 0x1p63);
    int64_t swapped = 0;
    for (int64_t db = 1; db <= cells; ++db) {
      // r = floor(db sqrt(2)) exactly: r² < 2 db² < (r + 1)².
      auto r = static_cast<int64_t>(std::sqrt(2.0) * static_cast<double>(db));
      while (r * r > 2 * db * db) --r;
      while ((r + 1) * (r + 1) < 2 * db * db) ++r;
      for (const int64_t da : {r, r + 1}) {
        // Path P has da more straight and db fewer diagonal steps than Q.
        const bool p_longer = da * da > 2 * db * db;
        const bool p_costlier = da * unit > db * diagonal;
        if (p_longer != p_costlier) ++swapped;
      }
    }
    EXPECT_EQ(swapped, 0) << w << " x " << h << ": unit " << c.unit
                          << ", diagonal " << c.diagonal;
  }
}

double Length(const std::vector<std::string>& rows, Connectivity c) {
  Cell s, g;
  const Grid grid = GridFromRows(rows, &s, &g);
  return GridPlanner(grid, c).Plan(s, g).length;
}

TEST(AStar, DiagonalStepsCostSqrt2AndNeverCutACorner) {
  const double r2 = std::sqrt(2.0);
  EXPECT_NEAR(Length({"S.", ".G"}, Connectivity::kEight), r2, 1e-12);
  // One blocked side cell forbids the diagonal: two straight steps.
  EXPECT_NEAR(Length({"S@", ".G"}, Connectivity::kEight), 2.0, 1e-12);
  EXPECT_NEAR(Length({"S.", "@G"}, Connectivity::kEight), 2.0, 1e-12);
  // Both blocked: the only way would squeeze between two corners.
  EXPECT_EQ(Length({"S@", "@G"}, Connectivity::kEight), -1.0);
  // An open room: 2 diagonal and 2 straight steps, or 6 straight ones.
  const std::vector<std::string> open = {"S....",  //
                                         ".....",  //
                                         "....G"};
  EXPECT_NEAR(Length(open, Connectivity::kEight), 2.0 + 2.0 * r2, 1e-12);
  EXPECT_NEAR(Length(open, Connectivity::kFour), 6.0, 1e-12);
  // Around a block, every diagonal would cut one of its corners: 6 straight
  // steps either way (cutting them would give 4 + sqrt(2)).
  const std::vector<std::string> room = {"S....",  //
                                         ".@@@.",  //
                                         "....G"};
  EXPECT_NEAR(Length(room, Connectivity::kEight), 6.0, 1e-12);
  EXPECT_NEAR(Length(room, Connectivity::kFour), 6.0, 1e-12);
}

TEST(AStar, FourConnectedWalksTheCorridorsOfAHandMadeMaze) {
  const std::vector<std::string> maze = {"S.@....",  //
                                         "@.@.@@.",  //
                                         "@...@G.",  //
                                         "@@@@@@@"};
  // S(0,0) -> (1,0) -> (1,2) -> (3,2) -> (3,0) -> (6,0) -> (6,2) -> (5,2).
  EXPECT_NEAR(Length(maze, Connectivity::kFour), 13.0, 1e-12);
  // 8-connected, the last step (6,1) -> (5,2) would cut the corner (5,1):
  // no diagonal is allowed anywhere, the same 13.
  EXPECT_NEAR(Length(maze, Connectivity::kEight), 13.0, 1e-12);
}

TEST(AStar, TiesGoToTheLargerG) {
  // On an empty grid every cell of the octile "parallelogram" between start
  // and goal has f = C*; preferring the larger g walks straight to the goal
  // and expands only the path's cells.
  const Grid grid(60, 40);
  GridPlanner planner(grid);
  const PlanResult r = planner.Plan({2, 3}, {55, 31});
  EXPECT_EQ(r.expansions, static_cast<int64_t>(r.path.size()));
}

TEST(AStar, StartAtTheGoalIsAZeroLengthPath) {
  const Grid grid(5, 5);
  GridPlanner planner(grid);
  const PlanResult r = planner.Plan({2, 2}, {2, 2});
  EXPECT_TRUE(r.found);
  EXPECT_EQ(r.length, 0.0);
  EXPECT_EQ(r.path.size(), 1u);
  EXPECT_EQ(r.expansions, 1);
}

TEST(AStar, NoPathIsAnAnswerNotAnError) {
  Cell s, g;
  const Grid grid = GridFromRows({"S.@..", "..@.G", "..@.."}, &s, &g);
  GridPlanner planner(grid);
  const PlanResult r = planner.Plan(s, g);
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.length, -1.0);
  EXPECT_TRUE(r.path.empty());
  EXPECT_EQ(r.expansions, 6);  // the whole left region
}

TEST(AStar, StartOrGoalOffTheGridOrBlockedThrows) {
  const Grid grid = GridFromRows({"..@", "..."});
  GridPlanner planner(grid);
  EXPECT_THROW(planner.Plan({-1, 0}, {0, 0}), std::invalid_argument);
  EXPECT_THROW(planner.Plan({0, 0}, {3, 0}), std::invalid_argument);
  EXPECT_THROW(planner.Plan({0, 0}, {0, 2}), std::invalid_argument);
  try {
    planner.Plan({0, 0}, {2, 0});
    ADD_FAILURE() << "a blocked goal was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "goal (2, 0) is a blocked cell");
  }
}

// Each defect of the notes on a map that shows it: the notes' version with
// that defect alone (and as written, all defects) is wrong there, the fixed
// version and navigation/astar.cc are right.
struct DefectCase {
  std::vector<std::string> rows;
  NotesDefects alone;
  SearchMode mode;
};

void ExpectDefectShown(const DefectCase& c) {
  Cell s, g;
  const Grid grid = GridFromRows(c.rows, &s, &g);
  const double optimal = ReferenceDijkstra(grid, s, g, true).length;
  ASSERT_GT(optimal, 0.0);
  NotesDefects as_written;
  as_written.zero_heuristic = c.alone.zero_heuristic;
  NotesDefects fixed{false, false, false, c.alone.zero_heuristic};
  const double alone = NotesAStar(grid, s, g, c.alone).length;
  const double written = NotesAStar(grid, s, g, as_written).length;
  EXPECT_NE(alone, optimal) << "the map does not show the defect";
  EXPECT_NE(written, optimal);
  EXPECT_NEAR(NotesAStar(grid, s, g, fixed).length, optimal, 1e-12);
  GridPlanner planner(grid);
  EXPECT_NEAR(planner.Plan(s, g, c.mode).length, optimal, 1e-12);
}

// "if j in open and cost < g(j): remove i from open": the goal's neighbour
// below-left is first reached diagonally from the row above... and keeps
// that longer way.
TEST(AStarNotesDefects, ACheaperWayLowersGFAndFather) {
  ExpectDefectShown({{"G@....",  //
                      "....S."},
                     {true, false, false, false},
                     SearchMode::kAStar});
}

// "while End not in open": with h = 0 (Dijkstra) the goal is first pushed
// from a diagonal neighbour at a larger cost than the straight way found
// later.
TEST(AStarNotesDefects, TheSearchStopsWhenTheGoalLeavesTheOpenList) {
  ExpectDefectShown({{"@S..",  //
                      "....",  //
                      ".@.@",  //
                      "....",  //
                      "....",  //
                      "G..."},
                     {false, true, false, true},
                     SearchMode::kDijkstra});
}

// "if count == 0: can't find path": the cell left of the start is a dead end
// nearer the goal (f = 1 + 2) than the way out (f = 1 + 2 sqrt(2)), so it
// is expanded first, whatever the tie rule, and has no new neighbour.
TEST(AStarNotesDefects, NoPathOnlyWhenTheOpenListIsEmpty) {
  ExpectDefectShown({{"G....",  //
                      "@@@@.",  //
                      ".S...",  //
                      "@@@@@"},
                     {false, false, true, false},
                     SearchMode::kAStar});
}

}  // namespace
}  // namespace vio
