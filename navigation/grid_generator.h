#ifndef VIO_NAVIGATION_GRID_GENERATOR_H_
#define VIO_NAVIGATION_GRID_GENERATOR_H_

// Seeded grids for tests and benchmarks (the same seed gives the same grid
// on every machine: std::mt19937 and integer arithmetic only).

#include <cstdint>
#include <utility>
#include <vector>

#include "navigation/grid.h"

namespace vio {

// Each cell blocked with probability blocked_fraction (in [0, 1]).
Grid RandomGrid(int width, int height, double blocked_fraction, uint32_t seed);

// A perfect maze (one way between any two corridor cells) carved by a
// randomised depth-first search: corridors 1 cell wide on the odd rows and
// columns, walls 1 cell thick.
Grid MazeGrid(int width, int height, uint32_t seed);

// The free cells of the largest connected region. 4-connected regions are
// also the 8-connected ones when diagonals may not cut corners (a diagonal
// step needs both straight cells beside it free).
std::vector<Cell> LargestRegion(const Grid& grid);

// `count` start-goal pairs drawn uniformly from LargestRegion(grid), so each
// has a path. Empty when the grid has no free cell.
std::vector<std::pair<Cell, Cell>> RandomQueries(const Grid& grid, int count,
                                                 uint32_t seed);

}  // namespace vio

#endif  // VIO_NAVIGATION_GRID_GENERATOR_H_
