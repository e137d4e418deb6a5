#ifndef VIO_NAVIGATION_MOVING_AI_H_
#define VIO_NAVIGATION_MOVING_AI_H_

// Moving AI Lab grid benchmark files (Sturtevant, "Benchmarks for Grid-Based
// Pathfinding", IEEE TCIAIG 4(2), 2012; the format page of the benchmarks).
//
// Map (.map):
//   type octile
//   height H
//   width W
//   map
//   H rows of W characters; (0, 0) is the upper-left cell, x the column.
// Passable: '.', 'G', 'S'. Blocked: '@', 'O' (out of bounds), 'T' (trees),
// 'W' (water: passable only from water in the benchmark; blocked here, as
// for a ground robot). Any other character is an error.
//
// Scenario (.scen): a first line "version 1" (or "version 1.0"), then one
// scenario per line, 9 fields separated by white space (tabs in the files):
//   bucket  map  map-width  map-height  start-x  start-y  goal-x  goal-y
//   optimal-length
// The optimal length assumes sqrt(2) diagonals and no corner cutting.
//
// Every malformed line throws NavigationError naming file and line:
// "maze.map:7: row 3 has 5 cells, the header says width 6".

#include <string>
#include <vector>

#include "navigation/grid.h"

namespace vio {

struct MovingAiScenario {
  int line = 0;  // 1-based line in the .scen file
  int bucket = 0;
  std::string map;  // as written in the file
  int map_width = 0;
  int map_height = 0;
  Cell start;
  Cell goal;
  double optimal_length = 0.0;  // [cells]
};

Grid ReadMovingAiMap(const std::string& path);
std::vector<MovingAiScenario> ReadMovingAiScenarios(const std::string& path);

// Throws NavigationError "scen_path:line: ..." when the scenario's map size
// is not the grid's, or its start or goal is off the grid or blocked.
void CheckScenario(const Grid& grid, const MovingAiScenario& scenario,
                   const std::string& scen_path);

// Writers ('.' free, '@' blocked; lengths with 8 decimals). Throw
// NavigationError when the file cannot be written.
void WriteMovingAiMap(const std::string& path, const Grid& grid);
void WriteMovingAiScenarios(const std::string& path,
                            const std::vector<MovingAiScenario>& scenarios);

}  // namespace vio

#endif  // VIO_NAVIGATION_MOVING_AI_H_
