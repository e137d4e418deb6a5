#ifndef VIO_NAVIGATION_ASTAR_H_
#define VIO_NAVIGATION_ASTAR_H_

// A* on a grid (Algorithm 1 of the user's notes, "time optimised A*"), with
// the notes' binary-heap open list, closed set, f = g + h and father pointers,
// and with the notes' defects fixed (docs/navigation.md):
//   - a cheaper way to a node already in the open list lowers its g, f and
//     father (lazy decrease-key: the node is pushed again with the lower f
//     and the stale entry is skipped when it surfaces). The notes remove the
//     expanded node from the open list instead, which keeps the first,
//     possibly longer, way;
//   - the search stops when the goal is TAKEN OUT of the open list, not when
//     it enters it: only then is its g the shortest (the notes' stop can
//     return a longer path);
//   - "no path" is an empty open list. The notes give up when one expanded
//     node has no new neighbour, which a dead end of a maze already does.
//
// Moves (Moving AI semantics): 8-connected with costs 1 (straight) and
// sqrt(2) (diagonal), where a diagonal step needs both cells beside it free
// (no corner cutting); or 4-connected with cost 1. The heuristic is the
// octile distance (8-connected) or the Manhattan distance (4-connected):
// both consistent, so the first time a node is taken out of the open list its
// g is final. Among equal f the node with the larger g is expanded first (it
// is nearer the goal). Dijkstra is the same search with h = 0.

#include <cstdint>
#include <vector>

#include "navigation/grid.h"

namespace vio {

enum class Connectivity { kFour, kEight };
enum class SearchMode { kAStar, kDijkstra };

struct PlanResult {
  bool found = false;
  double length = -1.0;    // [cells] sum of step costs; -1 when not found
  std::vector<Cell> path;  // start ... goal; empty when not found
  // Nodes taken out of the open list and expanded, the goal included [-].
  int64_t expansions = 0;
};

// One planner per grid: it keeps its buffers between queries, so a query
// costs nothing for the cells it does not touch.
class GridPlanner {
 public:
  // Copies the grid (later changes to it are not seen).
  explicit GridPlanner(const Grid& grid,
                       Connectivity connectivity = Connectivity::kEight);

  // The shortest path from start to goal. A query without a path is an
  // answer (found = false), not an error. Throws std::invalid_argument when
  // start or goal is off the grid or blocked.
  PlanResult Plan(Cell start, Cell goal, SearchMode mode = SearchMode::kAStar);

  int width() const { return width_; }
  int height() const { return height_; }
  Connectivity connectivity() const { return connectivity_; }

 private:
  struct Node {
    double g = 0.0;
    int32_t parent = -1;
    // 2 * generation_: g and parent belong to this query (open);
    // 2 * generation_ + 1: also expanded (closed). 16 bytes a node.
    uint32_t stamp = 0;
  };
  // 16 bytes: f decides the order; g (as a float) only breaks ties.
  struct OpenEntry {
    double f;
    float g;
    int32_t node;
  };

  void CheckEndpoint(Cell c, const char* name) const;
  void NextGeneration();
  template <bool kEightConnected, bool kHeuristic>
  bool Search(int32_t start, int32_t goal, int64_t* expansions);
  PlanResult Result(int32_t start, int32_t goal, bool found,
                    int64_t expansions) const;

  int width_;
  int height_;
  int stride_;  // width + 2: one blocked cell of padding on every side
  Connectivity connectivity_;
  std::vector<uint8_t> passable_;  // padded
  std::vector<Node> nodes_;        // padded
  std::vector<OpenEntry> open_;    // binary heap (LaterOut order)
  std::vector<OpenEntry> level_;   // successors at the current f (astar.cc)
  uint32_t generation_ = 0;        // < 2^31: stamps are 2 * generation_ (+ 1)
};

}  // namespace vio

#endif  // VIO_NAVIGATION_ASTAR_H_
