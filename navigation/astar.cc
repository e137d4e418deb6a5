#include "navigation/astar.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

// The moves, bit d of GridPlanner::cell_: 4 straight ones, then the
// diagonals. Successors are relaxed in this order; of those at the current f
// the last relaxed comes out first (a diagonal before a straight step).
constexpr int kDx[8] = {0, 0, -1, 1, -1, 1, -1, 1};
constexpr int kDy[8] = {-1, 1, 0, 0, -1, -1, 1, 1};
constexpr int kStraightMoves = 4;

// The bits of the smallest k with value < 2^k.
int BitWidth(uint64_t value) {
  int k = 0;
  while (k < 64 && (value >> k) != 0) ++k;
  return k;
}

}  // namespace

// Integer costs. A path of a straight and b diagonal steps has the length
// a + b sqrt(2) and the cost a S + b D, with S = 2^k and D = round(sqrt(2) S):
// |D - sqrt(2) S| <= 0.53 (0.5 from the rounding, < 0.03 from the double
// sqrt(2) scaled by 2^k <= 2^48). The search itself is exact in these
// integers (no sums of doubles), and the octile heuristic in the same units
// is consistent (it is the exact distance on an empty grid with these
// costs), so the path found has the least cost a S + b D.
//   Least cost is least length when the rounding cannot swap the order of
// two paths. Let P be the path found and Q a shortest one, both simple (b <=
// cells), Δa = a_P - a_Q, Δb = b_P - b_Q. Their costs differ by
//   S (Δa + Δb sqrt(2)) + Δb (D - sqrt(2) S),
// whose second term is at most 0.53 |Δb|. If Δb = 0 the costs compare as the
// lengths. Otherwise Δa + Δb sqrt(2) is not 0 (sqrt(2) is irrational) and,
// as |Δa² - 2 Δb²| >= 1, it is at least 1 / |Δa - Δb sqrt(2)| >= 1 / (2.9
// |Δb| + 1) when it is below 1 (when it is not, S > 0.53 |Δb| suffices). So the
// costs order P and Q as their lengths do when S > 0.53 |Δb| (2.9 |Δb| + 1),
// i.e. S > 1.6 Δb² + 0.6 |Δb|: then cost(P) <= cost(Q) forces length(P) <=
// length(Q), and P is a shortest path. Equal lengths have equal a and b, hence
// equal costs: ties of f are exact too, and the length returned is a + b
// sqrt(2) counted on the path, not the sum of costs.
//   k = min(48, 62 - BitWidth(cells + width + height)) keeps every f (g <= D
// cells, h <= D (width + height)) below 1.5 * 2^62 < 2^63, and meets the
// bound above for every grid of up to 2^20 cells (k >= 41 there; 512 x 512
// has k = 43 and needs k > 37). astar_test's
// FixedPointCostsOrderPathsAsTheirLengths checks, for the Δb of those grids and
// the Δa nearest -Δb sqrt(2) (the hardest pairs), that the costs compare as the
// lengths.
//   Larger grids keep this order unless two lengths differ by less than
// 0.53 |Δb| / S, about 1e-10 |Δb| cells at 2^28 cells; summing doubles (the
// planner before these integers) erred by more there.
StepCosts FixedPointStepCosts(int width, int height) {
  const uint64_t bound = static_cast<uint64_t>(width) * height +
                         static_cast<uint64_t>(width) + height;
  const int k = std::min(48, 62 - BitWidth(bound));
  return {uint64_t{1} << k,
          static_cast<uint64_t>(std::llround(std::ldexp(kSqrt2, k)))};
}

GridPlanner::GridPlanner(const Grid& grid, Connectivity connectivity)
    : width_(grid.width()),
      height_(grid.height()),
      stride_(grid.width() + 2),
      connectivity_(connectivity) {
  const StepCosts costs = FixedPointStepCosts(width_, height_);
  unit_ = costs.unit;
  diagonal_ = costs.diagonal;

  passable_.assign(static_cast<size_t>(stride_) * (height_ + 2), 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      passable_[static_cast<size_t>(y + 1) * stride_ + x + 1] =
          grid.Blocked({x, y}) ? 0 : 1;
    }
  }
  // The allowed moves of every cell, once: a diagonal step needs both cells
  // beside it free (no corner cutting). The blocked border has none.
  const int moves = connectivity == Connectivity::kEight ? 8 : kStraightMoves;
  cell_.assign(passable_.size(), 0);
  for (int y = 1; y <= height_; ++y) {
    for (int x = 1; x <= width_; ++x) {
      const size_t i = static_cast<size_t>(y) * stride_ + x;
      if (!passable_[i]) continue;
      for (int d = 0; d < moves; ++d) {
        const bool free = passable_[i + kDy[d] * stride_ + kDx[d]] &&
                          passable_[i + kDx[d]] &&
                          passable_[i + kDy[d] * stride_];
        if (free) cell_[i] |= 1u << d;
      }
    }
  }
  g_.resize(passable_.size());
}

int32_t GridPlanner::Offset(int d) const { return kDy[d] * stride_ + kDx[d]; }

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
  if (++generation_ == (1u << 20)) {  // after 2^20 queries: clear the stamps
    for (uint32_t& word : cell_) word &= kMovesMask;
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
// The open list is open_ (navigation/open_list.h) plus level_, a stack of
// the successors whose f equals the f being expanded. With a consistent h no
// open node has a smaller f, and such a successor's g exceeds that of every
// open node with the same f (the expanded one had the largest), so open_
// would return it next: it skips open_. Most expansions on open ground are
// of this kind (f stays constant along a straight or diagonal run toward
// the goal).
template <bool kEightConnected, bool kHeuristic>
bool GridPlanner::Search(int32_t start, int32_t goal, int64_t* expansions) {
  const int gx = goal % stride_;
  const int gy = goal / stride_;
  const uint64_t unit = unit_;
  const uint64_t extra = diagonal_ - unit_;  // a diagonal minus a straight
  auto h = [&](int x, int y) -> uint64_t {
    if (!kHeuristic) return 0;
    const uint64_t dx = static_cast<uint64_t>(std::abs(x - gx));
    const uint64_t dy = static_cast<uint64_t>(std::abs(y - gy));
    if (!kEightConnected) return (dx + dy) * unit;  // Manhattan
    // Octile: min(dx, dy) diagonal steps and |dx - dy| straight ones.
    return std::max(dx, dy) * unit + std::min(dx, dy) * extra;
  };
  int32_t offset[8];
  uint64_t cost[8];
  for (int d = 0; d < 8; ++d) {
    offset[d] = Offset(d);
    cost[d] = d < kStraightMoves ? unit_ : diagonal_;
  }

  const uint32_t open = generation_ << kGenerationShift;  // this query's
  const uint32_t closed = open | kClosed;
  cell_[start] = (cell_[start] & kMovesMask) | open;
  g_[start] = 0;
  const uint64_t start_f = h(start % stride_, start / stride_);
  // A successor's f exceeds the expanded node's by at most twice the step.
  open_.Reset(start_f, 2 * (kEightConnected ? diagonal_ : unit_));
  open_.Push(start_f, 0, start);
  level_.clear();

  while (true) {
    OpenList::Entry top;
    if (!level_.empty()) {
      top = level_.back();
      level_.pop_back();
    } else if (!open_.empty()) {
      top = open_.Pop();
    } else {
      break;
    }
    const int32_t n = top.node;
    // Lazy deletion: an entry left behind by a decrease-key is skipped. Its
    // node was pushed again with a lower g, so (h being the same) a lower f,
    // and has been expanded by the time the old entry surfaces.
    const uint32_t word = cell_[n];
    if ((word & kStateMask) == closed) continue;
    cell_[n] = word | kClosed;
    ++*expansions;
    if (n == goal) return true;  // taken out of open: g is final

    const int x = n % stride_;
    const int y = n / stride_;
    const uint64_t g = g_[n];
    // Relaxes each allowed move (one bit each, precomputed): a first or a
    // cheaper way to the neighbour lowers its g, f and father and
    // (re)pushes it.
    for (uint32_t moves = word & kMovesMask; moves != 0; moves &= moves - 1) {
      const int d = __builtin_ctz(moves);
      const int32_t m = n + offset[d];
      const uint32_t next = cell_[m];
      const uint32_t state = next & kStateMask;
      if (state == closed) continue;
      const uint64_t ng = g + cost[d];
      if (state == open && ng >= g_[m]) continue;
      g_[m] = ng;
      cell_[m] =
          (next & kMovesMask) | open | static_cast<uint32_t>(d) << kFatherShift;
      const uint64_t f = ng + h(x + kDx[d], y + kDy[d]);
      const uint32_t g_tie = static_cast<uint32_t>(ng >> 31);
      if (f == top.f) {
        level_.emplace_back(f, g_tie, m);  // comes out next anyway: skip open_
      } else {
        open_.Push(f, g_tie, m);
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
  for (int32_t n = goal;; n -= Offset((cell_[n] >> kFatherShift) & 7)) {
    r.path.push_back({n % stride_ - 1, n / stride_ - 1});
    if (n == start) break;
  }
  std::reverse(r.path.begin(), r.path.end());
  // The length a + b sqrt(2) of its a straight and b diagonal steps.
  int64_t straight = 0, diagonal = 0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const bool is_diagonal =
        r.path[i].x != r.path[i - 1].x && r.path[i].y != r.path[i - 1].y;
    ++(is_diagonal ? diagonal : straight);
  }
  r.length = static_cast<double>(straight) + kSqrt2 * diagonal;
  return r;
}

}  // namespace vio
