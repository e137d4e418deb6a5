#ifndef VIO_TEST_TESTING_GRID_SEARCH_REFERENCE_H_
#define VIO_TEST_TESTING_GRID_SEARCH_REFERENCE_H_

// Reference searches for the A* tests, written apart from navigation/astar.cc:
//   - ReferenceDijkstra: a plain Dijkstra with bounds checks, its own
//     corner-cutting rule and std::priority_queue;
//   - NotesAStar: Algorithm 1 of the user's notes as written, with a switch
//     per defect so that a test can show each defect alone.

#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "navigation/astar.h"
#include "navigation/grid.h"

namespace vio {
namespace testing {

struct ReferenceResult {
  bool found = false;
  double length = -1.0;
  int64_t expansions = 0;
};

// The moves from c: (neighbour, cost). Diagonals only when both straight
// cells beside them are free (Moving AI: no corner cutting).
inline std::vector<std::pair<Cell, double>> Moves(const Grid& grid, Cell c,
                                                  bool eight) {
  std::vector<std::pair<Cell, double>> moves;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const Cell n{c.x + dx, c.y + dy};
      if (!grid.Free(n)) continue;
      if (dx != 0 && dy != 0) {
        if (!eight) continue;
        if (!grid.Free({c.x + dx, c.y}) || !grid.Free({c.x, c.y + dy})) {
          continue;
        }
        moves.push_back({n, std::sqrt(2.0)});
      } else {
        moves.push_back({n, 1.0});
      }
    }
  }
  return moves;
}

inline ReferenceResult ReferenceDijkstra(const Grid& grid, Cell start,
                                         Cell goal, bool eight) {
  const int w = grid.width();
  auto id = [w](Cell c) { return c.y * w + c.x; };
  std::vector<double> dist(static_cast<size_t>(w) * grid.height(), INFINITY);
  std::vector<bool> done(dist.size(), false);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[id(start)] = 0.0;
  queue.push({0.0, id(start)});
  ReferenceResult r;
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (done[i]) continue;
    done[i] = true;
    ++r.expansions;
    if (i == id(goal)) {
      r.found = true;
      r.length = d;
      return r;
    }
    for (const auto& [n, cost] : Moves(grid, {i % w, i / w}, eight)) {
      if (d + cost < dist[id(n)]) {
        dist[id(n)] = d + cost;
        queue.push({d + cost, id(n)});
      }
    }
  }
  return r;
}

// Which of the notes' defects to keep (all true: the notes as written).
struct NotesDefects {
  // "if j in open and cost < g(j) then remove i from open": j keeps its
  // first g and father.
  bool no_decrease_key = true;
  // "while End node not in open": stops when End is pushed.
  bool stop_when_goal_enters_open = true;
  // "if count == 0 then can't find path": gives up at the first expanded
  // node without a new neighbour.
  bool give_up_at_dead_end = true;
  // Not a defect: h = 0 (Dijkstra) instead of the octile distance. With the
  // octile distance the early stop happens to be harmless on unit grids (a
  // goal's neighbour has h equal to its move cost); with any h that
  // underestimates that move, such as 0, it is not.
  bool zero_heuristic = false;
};

// Algorithm 1 of the notes, 8-connected with the octile heuristic (or h = 0).
// Ties in the heap are broken by node index (the notes do not say). An empty
// open list, where the notes would take the minimum of nothing, is "no path".
inline ReferenceResult NotesAStar(const Grid& grid, Cell start, Cell end,
                                  const NotesDefects& defects) {
  const int w = grid.width();
  auto id = [w](Cell c) { return c.y * w + c.x; };
  auto h = [&](Cell c) {
    if (defects.zero_heuristic) return 0.0;
    const int dx = std::abs(c.x - end.x), dy = std::abs(c.y - end.y);
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
  };
  const size_t n = static_cast<size_t>(w) * grid.height();
  std::vector<double> g(n, 0.0);
  std::vector<int> father(n, -1);
  std::vector<bool> in_open(n, false), closed(n, false);
  using Item = std::pair<double, int>;  // (f, node)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  open.push({h(start), id(start)});
  in_open[id(start)] = true;
  ReferenceResult r;
  while (!(defects.stop_when_goal_enters_open && in_open[id(end)])) {
    if (open.empty()) return r;
    const int i = open.top().second;
    open.pop();
    if (closed[i]) continue;  // a stale entry of a lowered node
    in_open[i] = false;
    closed[i] = true;
    ++r.expansions;
    if (!defects.stop_when_goal_enters_open && i == id(end)) break;
    int count = 0;
    for (const auto& [j_cell, cost_ij] : Moves(grid, {i % w, i / w}, true)) {
      const int j = id(j_cell);
      if (closed[j]) continue;
      ++count;
      const double cost = g[i] + cost_ij;
      if (in_open[j] && cost < g[j] && !defects.no_decrease_key) {
        g[j] = cost;
        father[j] = i;
        open.push({cost + h(j_cell), j});
      }
      if (!in_open[j] && !closed[j]) {
        in_open[j] = true;
        g[j] = cost;
        father[j] = i;
        open.push({cost + h(j_cell), j});
      }
    }
    if (count == 0 && defects.give_up_at_dead_end) return r;
  }
  r.found = true;
  r.length = g[id(end)];
  return r;
}

// A grid from rows of '.' (free) and '@' (blocked); 'S' and 'G' mark free
// start and goal cells, returned through start and goal when given.
inline Grid GridFromRows(const std::vector<std::string>& rows,
                         Cell* start = nullptr, Cell* goal = nullptr) {
  Grid grid(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const char c = rows[y][x];
      grid.SetBlocked({x, y}, c == '@');
      if (c == 'S' && start) *start = {x, y};
      if (c == 'G' && goal) *goal = {x, y};
    }
  }
  return grid;
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_GRID_SEARCH_REFERENCE_H_
