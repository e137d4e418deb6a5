#include "navigation/astar.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

// Two f closer than this [cells] are equal (sums of 1 and sqrt(2) rounded
// in different orders differ in their last bits).
constexpr double kSameF = 1e-9;

// The open list's order: std::push_heap keeps the "largest" on top, so an
// entry is "less" when it should come out later: a larger f, or an equal f
// with a smaller g (ties go to the larger g).
struct LaterOut {
  template <typename E>
  bool operator()(const E& a, const E& b) const {
    return a.f > b.f || (a.f == b.f && a.g < b.g);
  }
};

// Octile distance: min(dx, dy) diagonal steps and |dx - dy| straight ones.
inline double Octile(int dx, int dy) {
  const int lo = std::min(dx, dy);
  const int hi = std::max(dx, dy);
  return (hi - lo) + kSqrt2 * lo;
}

}  // namespace

GridPlanner::GridPlanner(const Grid& grid, Connectivity connectivity)
    : width_(grid.width()),
      height_(grid.height()),
      stride_(grid.width() + 2),
      connectivity_(connectivity) {
  passable_.assign(static_cast<size_t>(stride_) * (height_ + 2), 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      passable_[static_cast<size_t>(y + 1) * stride_ + x + 1] =
          grid.Blocked({x, y}) ? 0 : 1;
    }
  }
  nodes_.resize(passable_.size());
}

void GridPlanner::CheckEndpoint(Cell c, const char* name) const {
  const std::string where = std::string(name) + " (" + std::to_string(c.x) +
                            ", " + std::to_string(c.y) + ")";
  if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) {
    throw std::invalid_argument(where + " is off the " +
                                std::to_string(width_) + " x " +
                                std::to_string(height_) + " grid");
  }
  if (!passable_[static_cast<size_t>(c.y + 1) * stride_ + c.x + 1]) {
    throw std::invalid_argument(where + " is a blocked cell");
  }
}

void GridPlanner::NextGeneration() {
  if (++generation_ == (1u << 31)) {  // after 2^31 queries: clear the stamps
    for (Node& n : nodes_) n.stamp = 0;
    generation_ = 1;
  }
}

PlanResult GridPlanner::Plan(Cell start, Cell goal, SearchMode mode) {
  CheckEndpoint(start, "start");
  CheckEndpoint(goal, "goal");
  NextGeneration();
  const int32_t s = (start.y + 1) * stride_ + start.x + 1;
  const int32_t t = (goal.y + 1) * stride_ + goal.x + 1;
  const bool eight = connectivity_ == Connectivity::kEight;
  const bool astar = mode == SearchMode::kAStar;
  int64_t expansions = 0;
  bool found;
  if (eight) {
    found = astar ? Search<true, true>(s, t, &expansions)
                  : Search<true, false>(s, t, &expansions);
  } else {
    found = astar ? Search<false, true>(s, t, &expansions)
                  : Search<false, false>(s, t, &expansions);
  }
  return Result(s, t, found, expansions);
}

// One query. Nodes are indices into the padded grid, whose border is
// blocked, so a neighbour never needs a bounds check.
//
// The open list is the binary heap plus level_, a stack of the successors
// whose f equals the f being expanded. With a consistent h no open node has
// a smaller f, and such a successor's g exceeds that of every node in the
// heap with the same f (the expanded one had the largest), so the heap
// would return it next: it skips the heap's push and pop. Most expansions
// on open ground are of this kind (f stays constant along a straight or
// diagonal run toward the goal).
template <bool kEightConnected, bool kHeuristic>
bool GridPlanner::Search(int32_t start, int32_t goal, int64_t* expansions) {
  const int gx = goal % stride_;
  const int gy = goal / stride_;
  auto h = [&](int x, int y) -> double {
    if (!kHeuristic) return 0.0;
    const int dx = std::abs(x - gx);
    const int dy = std::abs(y - gy);
    return kEightConnected ? Octile(dx, dy) : static_cast<double>(dx + dy);
  };
  open_.clear();
  level_.clear();
  const uint32_t open = 2 * generation_;  // node stamps of this query
  const uint32_t closed = open + 1;
  Node& s = nodes_[start];
  s.g = 0.0;
  s.parent = -1;
  s.stamp = 2 * generation_;
  open_.push_back({h(start % stride_, start / stride_), 0.0f, start});

  while (true) {
    OpenEntry top;
    if (!level_.empty()) {
      top = level_.back();
      level_.pop_back();
    } else if (!open_.empty()) {
      std::pop_heap(open_.begin(), open_.end(), LaterOut());
      top = open_.back();
      open_.pop_back();
    } else {
      break;
    }
    Node& current = nodes_[top.node];
    // Lazy deletion: an entry left behind by a decrease-key is skipped. Its
    // node was pushed again with a lower g, so (h being the same) a lower f,
    // and has been expanded by the time the old entry surfaces.
    if (current.stamp == closed) continue;
    current.stamp = closed;
    ++*expansions;
    if (top.node == goal) return true;  // taken out of open: g is final

    const int32_t n = top.node;
    const int x = n % stride_;
    const int y = n / stride_;
    const double g = current.g;
    // Relaxes the move to m (cost c): a first or a cheaper way lowers its g,
    // f and father and (re)pushes it.
    auto relax = [&](int32_t m, int mx, int my, double c) {
      Node& next = nodes_[m];
      if (next.stamp == closed) return;
      const double ng = g + c;
      if (next.stamp == open && ng >= next.g) return;
      next.g = ng;
      next.parent = n;
      next.stamp = open;
      const OpenEntry entry{ng + h(mx, my), static_cast<float>(ng), m};
      if (entry.f <= top.f + kSameF) {
        level_.push_back(entry);  // comes out next anyway: skip the heap
      } else {
        open_.push_back(entry);
        std::push_heap(open_.begin(), open_.end(), LaterOut());
      }
    };
    const bool north = passable_[n - stride_];
    const bool south = passable_[n + stride_];
    const bool west = passable_[n - 1];
    const bool east = passable_[n + 1];
    if (north) relax(n - stride_, x, y - 1, 1.0);
    if (south) relax(n + stride_, x, y + 1, 1.0);
    if (west) relax(n - 1, x - 1, y, 1.0);
    if (east) relax(n + 1, x + 1, y, 1.0);
    if (kEightConnected) {
      // A diagonal step needs both cells beside it free (no corner cutting).
      if (north && west && passable_[n - stride_ - 1]) {
        relax(n - stride_ - 1, x - 1, y - 1, kSqrt2);
      }
      if (north && east && passable_[n - stride_ + 1]) {
        relax(n - stride_ + 1, x + 1, y - 1, kSqrt2);
      }
      if (south && west && passable_[n + stride_ - 1]) {
        relax(n + stride_ - 1, x - 1, y + 1, kSqrt2);
      }
      if (south && east && passable_[n + stride_ + 1]) {
        relax(n + stride_ + 1, x + 1, y + 1, kSqrt2);
      }
    }
  }
  return false;  // open list empty: no path
}

PlanResult GridPlanner::Result(int32_t start, int32_t goal, bool found,
                               int64_t expansions) const {
  PlanResult r;
  r.found = found;
  r.expansions = expansions;
  if (!found) return r;
  r.length = nodes_[goal].g;
  for (int32_t n = goal; n != -1; n = nodes_[n].parent) {
    r.path.push_back({n % stride_ - 1, n / stride_ - 1});
    if (n == start) break;
  }
  std::reverse(r.path.begin(), r.path.end());
  return r;
}

}  // namespace vio
