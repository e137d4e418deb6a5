// A* (navigation/astar.h) against our Dijkstra (the same search with h = 0)
// and Boost Graph's astar_search on the same 512 x 512 grids and the same
// queries, in one run: random obstacles at 10, 20 and 30 % and a maze, made
// by the seeded generators of navigation/grid_generator.h. One iteration is
// the same 100 start-goal pairs of the grid's largest region for all three
// (time per query = time / 100; items/s = queries/s). Counters: expansions
// per query and expansions per second (nodes taken out of the open list and
// expanded; Boost: examine_vertex calls).
// Before timing, every query's length is checked equal across the three.
// Run: ./build/test/benchmark/astar_benchmark
//
// Boost is used as its documentation shows: an adjacency_list of the free
// 8-connected moves (no corner cutting), astar_search with vector-backed
// property maps allocated once, and a visitor that stops at the goal. Its
// astar_search initialises every vertex per query (O(cells)); ours keeps
// per-cell stamps between queries instead.

#include <benchmark/benchmark.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/astar_search.hpp>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "navigation/astar.h"
#include "navigation/grid_generator.h"

namespace vio {
namespace {

constexpr int kSide = 512;
constexpr int kQueries = 100;

using BoostGraph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS,
                          boost::no_property,
                          boost::property<boost::edge_weight_t, double>>;
using BoostVertex = boost::graph_traits<BoostGraph>::vertex_descriptor;

// The grid's moves as a Boost graph: vertex y * width + x.
BoostGraph ToBoost(const Grid& grid) {
  const int w = grid.width();
  BoostGraph g(static_cast<size_t>(w) * grid.height());
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < w; ++x) {
      if (grid.Blocked({x, y})) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || !grid.Free({x + dx, y + dy})) continue;
          const bool diagonal = dx != 0 && dy != 0;
          if (diagonal &&
              (!grid.Free({x + dx, y}) || !grid.Free({x, y + dy}))) {
            continue;
          }
          boost::add_edge(y * w + x, (y + dy) * w + x + dx,
                          diagonal ? std::sqrt(2.0) : 1.0, g);
        }
      }
    }
  }
  return g;
}

class OctileHeuristic : public boost::astar_heuristic<BoostGraph, double> {
 public:
  OctileHeuristic(int width, Cell goal) : width_(width), goal_(goal) {}
  double operator()(BoostVertex v) const {
    const int dx = std::abs(static_cast<int>(v) % width_ - goal_.x);
    const int dy = std::abs(static_cast<int>(v) / width_ - goal_.y);
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
  }

 private:
  int width_;
  Cell goal_;
};

struct FoundGoal {};

class StopAtGoal : public boost::default_astar_visitor {
 public:
  StopAtGoal(BoostVertex goal, int64_t* examined)
      : goal_(goal), examined_(examined) {}
  void examine_vertex(BoostVertex v, const BoostGraph&) {
    ++*examined_;
    if (v == goal_) throw FoundGoal();
  }

 private:
  BoostVertex goal_;
  int64_t* examined_;
};

// Boost's astar_search with its property maps kept between queries.
class BoostPlanner {
 public:
  explicit BoostPlanner(const Grid& grid)
      : width_(grid.width()),
        graph_(ToBoost(grid)),
        predecessor_(boost::num_vertices(graph_)),
        distance_(boost::num_vertices(graph_)),
        rank_(boost::num_vertices(graph_)),
        colour_(boost::num_vertices(graph_)) {}

  // The path length (-1 without a path) and the vertices examined.
  std::pair<double, int64_t> Plan(Cell start, Cell goal) {
    const BoostVertex s = start.y * width_ + start.x;
    const BoostVertex t = goal.y * width_ + goal.x;
    int64_t examined = 0;
    try {
      boost::astar_search(
          graph_, s, OctileHeuristic(width_, goal),
          boost::predecessor_map(boost::make_iterator_property_map(
                                     predecessor_.begin(),
                                     boost::get(boost::vertex_index, graph_)))
              .distance_map(boost::make_iterator_property_map(
                  distance_.begin(), boost::get(boost::vertex_index, graph_)))
              .rank_map(boost::make_iterator_property_map(
                  rank_.begin(), boost::get(boost::vertex_index, graph_)))
              .color_map(boost::make_iterator_property_map(
                  colour_.begin(), boost::get(boost::vertex_index, graph_)))
              .visitor(StopAtGoal(t, &examined)));
    } catch (const FoundGoal&) {
      return {distance_[t], examined};
    }
    return {-1.0, examined};
  }

 private:
  int width_;
  BoostGraph graph_;
  std::vector<BoostVertex> predecessor_;
  std::vector<double> distance_;
  std::vector<double> rank_;
  std::vector<boost::default_color_type> colour_;
};

struct Scene {
  Grid grid;
  std::vector<std::pair<Cell, Cell>> queries;
  std::unique_ptr<GridPlanner> ours;
  std::unique_ptr<BoostPlanner> boost;
  bool lengths_agree = true;
};

// 0, 1, 2: random at 10, 20, 30 %; 3: the maze. Built once, checked once.
Scene& GetScene(int which) {
  static std::unique_ptr<Scene> scenes[4];
  if (!scenes[which]) {
    auto s = std::make_unique<Scene>();
    s->grid = which < 3
                  ? RandomGrid(kSide, kSide, 0.1 * (which + 1), 42 + which)
                  : MazeGrid(kSide, kSide, 42);
    s->queries = RandomQueries(s->grid, kQueries, 7 + which);
    s->ours = std::make_unique<GridPlanner>(s->grid);
    s->boost = std::make_unique<BoostPlanner>(s->grid);
    for (const auto& [a, b] : s->queries) {
      const double astar = s->ours->Plan(a, b).length;
      const double dijkstra = s->ours->Plan(a, b, SearchMode::kDijkstra).length;
      const double boost = s->boost->Plan(a, b).first;
      if (std::abs(astar - dijkstra) > 1e-9 || std::abs(astar - boost) > 1e-9) {
        s->lengths_agree = false;
      }
    }
    scenes[which] = std::move(s);
  }
  return *scenes[which];
}

enum Planner { kOurAStar, kOurDijkstra, kBoostAStar };

void Run(benchmark::State& state, Planner planner) {
  Scene& scene = GetScene(static_cast<int>(state.range(0)));
  if (!scene.lengths_agree) {
    state.SkipWithError("the three planners disagree on a length");
    return;
  }
  int64_t expansions = 0, queries = 0;
  for (auto _ : state) {
    for (const auto& [a, b] : scene.queries) {
      if (planner == kBoostAStar) {
        expansions += scene.boost->Plan(a, b).second;
      } else {
        const PlanResult r = scene.ours->Plan(
            a, b,
            planner == kOurAStar ? SearchMode::kAStar : SearchMode::kDijkstra);
        expansions += r.expansions;
        benchmark::DoNotOptimize(r.length);
      }
      ++queries;
    }
  }
  state.SetItemsProcessed(queries);  // items/s: queries per second
  state.counters["expansions/query"] =
      static_cast<double>(expansions) / std::max<int64_t>(1, queries);
  state.counters["expansions/s"] = benchmark::Counter(
      static_cast<double>(expansions), benchmark::Counter::kIsRate);
}

void Arguments(benchmark::internal::Benchmark* b) {
  b->ArgName("map")->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
  b->MinTime(1.0);
}

void BM_OurAStar(benchmark::State& s) { Run(s, kOurAStar); }
void BM_OurDijkstra(benchmark::State& s) { Run(s, kOurDijkstra); }
void BM_BoostAStar(benchmark::State& s) { Run(s, kBoostAStar); }
BENCHMARK(BM_OurAStar)->Apply(Arguments);
BENCHMARK(BM_OurDijkstra)->Apply(Arguments);
BENCHMARK(BM_BoostAStar)->Apply(Arguments);

}  // namespace
}  // namespace vio

BENCHMARK_MAIN();
