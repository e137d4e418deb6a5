#include "navigation/grid_generator.h"

#include <random>
#include <stdexcept>

namespace vio {
namespace {

// A uniform integer in [0, n) that does not depend on the standard library's
// distribution implementation (those differ between vendors).
int Uniform(std::mt19937* rng, int n) {
  return static_cast<int>((static_cast<uint64_t>((*rng)()) * n) >> 32);
}

}  // namespace

Grid RandomGrid(int width, int height, double blocked_fraction, uint32_t seed) {
  if (!(blocked_fraction >= 0.0 && blocked_fraction <= 1.0)) {
    throw std::invalid_argument("RandomGrid: blocked_fraction not in [0, 1]");
  }
  Grid grid(width, height);
  std::mt19937 rng(seed);
  const uint64_t threshold =
      static_cast<uint64_t>(blocked_fraction * 4294967296.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) grid.SetBlocked({x, y}, rng() < threshold);
  }
  return grid;
}

Grid MazeGrid(int width, int height, uint32_t seed) {
  Grid grid(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) grid.SetBlocked({x, y}, true);
  }
  // Rooms at odd (x, y); carving a step of 2 opens the wall between.
  const int rooms_x = width / 2;
  const int rooms_y = height / 2;
  if (rooms_x < 1 || rooms_y < 1) return grid;
  std::mt19937 rng(seed);
  std::vector<uint8_t> visited(static_cast<size_t>(rooms_x) * rooms_y, 0);
  std::vector<Cell> stack = {{0, 0}};
  visited[0] = 1;
  grid.SetBlocked({1, 1}, false);
  const int dx[4] = {1, -1, 0, 0};
  const int dy[4] = {0, 0, 1, -1};
  while (!stack.empty()) {
    const Cell room = stack.back();
    int options[4];
    int n = 0;
    for (int d = 0; d < 4; ++d) {
      const int nx = room.x + dx[d];
      const int ny = room.y + dy[d];
      if (nx >= 0 && ny >= 0 && nx < rooms_x && ny < rooms_y &&
          !visited[static_cast<size_t>(ny) * rooms_x + nx]) {
        options[n++] = d;
      }
    }
    if (n == 0) {
      stack.pop_back();
      continue;
    }
    const int d = options[Uniform(&rng, n)];
    const Cell next{room.x + dx[d], room.y + dy[d]};
    visited[static_cast<size_t>(next.y) * rooms_x + next.x] = 1;
    grid.SetBlocked({2 * room.x + 1 + dx[d], 2 * room.y + 1 + dy[d]}, false);
    grid.SetBlocked({2 * next.x + 1, 2 * next.y + 1}, false);
    stack.push_back(next);
  }
  return grid;
}

std::vector<Cell> LargestRegion(const Grid& grid) {
  const int w = grid.width();
  std::vector<int> label(static_cast<size_t>(w) * grid.height(), -1);
  std::vector<Cell> best;
  std::vector<Cell> region;
  int next_label = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < w; ++x) {
      if (grid.Blocked({x, y}) || label[static_cast<size_t>(y) * w + x] >= 0) {
        continue;
      }
      region.clear();
      region.push_back({x, y});
      label[static_cast<size_t>(y) * w + x] = next_label;
      for (size_t i = 0; i < region.size(); ++i) {  // breadth-first fill
        const Cell c = region[i];
        const Cell around[4] = {
            {c.x + 1, c.y}, {c.x - 1, c.y}, {c.x, c.y + 1}, {c.x, c.y - 1}};
        for (const Cell& n : around) {
          if (!grid.Free(n)) continue;
          int& l = label[static_cast<size_t>(n.y) * w + n.x];
          if (l >= 0) continue;
          l = next_label;
          region.push_back(n);
        }
      }
      ++next_label;
      if (region.size() > best.size()) best = region;
    }
  }
  return best;
}

std::vector<std::pair<Cell, Cell>> RandomQueries(const Grid& grid, int count,
                                                 uint32_t seed) {
  const std::vector<Cell> region = LargestRegion(grid);
  std::vector<std::pair<Cell, Cell>> queries;
  if (region.empty()) return queries;
  std::mt19937 rng(seed);
  const int n = static_cast<int>(region.size());
  for (int i = 0; i < count; ++i) {
    const Cell a = region[Uniform(&rng, n)];
    const Cell b = region[Uniform(&rng, n)];
    queries.emplace_back(a, b);
  }
  return queries;
}

}  // namespace vio
