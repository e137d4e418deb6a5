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
#include "navigation/open_list.h"

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

// The integer step costs of the planner for a width x height grid: a
// straight step costs unit = 2^k, a diagonal one diagonal = round(sqrt(2) 2^k),
// k as large as the grid allows without overflow. astar.cc says why the
// order of these costs is the order of the path lengths (so the path found is
// a shortest one); astar_test checks it.
struct StepCosts {
  uint64_t unit;
  uint64_t diagonal;
};
StepCosts FixedPointStepCosts(int width, int height);

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
  // Costs and keys are integers: FixedPointStepCosts (unit_, diagonal_).
  // One 32-bit word per cell, so that the loop touches two arrays (12
  // bytes a cell, g_ apart: most neighbours looked at are closed, and only
  // their word is read):
  //   bits 0-7: the moves allowed from the cell (bit d: move d, fixed);
  //   bits 8-10: the move d by which its father reached it (the father is
  //     the cell - Offset(d));
  //   bit 11: expanded (closed);
  //   bits 12-31: the generation_ (query) that gave it a g and a father.
  // The cell is open in this query when bits 11-31 are generation_ << 12,
  // closed when they are that + kClosed.
  static constexpr uint32_t kMovesMask = 0xff;
  static constexpr int kFatherShift = 8;
  static constexpr uint32_t kClosed = 1u << 11;
  static constexpr int kGenerationShift = 12;
  static constexpr uint32_t kStateMask = ~uint32_t{0} << 11;

  // Move d in 0..7 (astar.cc: 4 straight, then 4 diagonal) as an index step.
  int32_t Offset(int d) const;
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
  uint64_t unit_;                  // cost of a straight step (1 cell)
  uint64_t diagonal_;              // cost of a diagonal step (sqrt(2) cells)
  std::vector<uint8_t> passable_;  // padded
  std::vector<uint32_t> cell_;     // padded; the words above
  std::vector<uint64_t> g_;        // padded; valid when stamped
  OpenList open_;                  // navigation/open_list.h
  std::vector<OpenList::Entry> level_;  // successors at the current f
  uint32_t generation_ = 0;             // < 2^20
};

}  // namespace vio

#endif  // VIO_NAVIGATION_ASTAR_H_
