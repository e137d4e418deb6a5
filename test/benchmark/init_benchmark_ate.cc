#include "test/benchmark/init_benchmark_ate.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "config/simulator_config.h"
#include "dataset/simulator.h"
#include "test/benchmark/distribution.h"
#include "test/testing/cut_simulation.h"
#include "test/testing/sim_replay.h"
#include "test/testing/spread.h"

namespace vio {
namespace {

SimulatorOptions LoadPreset(const std::string& preset) {
  return LoadSimulatorOptions(std::string(VIO_SOURCE_DIR) + "/config/sim_" +
                              preset + ".yaml");
}

// Run k of n: its seed and start phase (spread over one lap).
SimulatorOptions RunOptions(const SimulatorOptions& base, int k, int n) {
  SimulatorOptions o = base;
  o.seed = static_cast<uint32_t>(2000 + k);
  o.motion.start_phase_s =
      base.motion.start_phase_s + k * base.motion.lap_period_s / n;
  return o;
}

// The stamp of the first initialised output (INT64_MAX: none).
int64_t FirstEstimate(const std::vector<EstimatorOutput>& outputs) {
  for (const EstimatorOutput& o : outputs) {
    if (o.processed && o.initialized) return o.t_ns;
  }
  return INT64_MAX;
}

// ATE of `run` against `sim`'s truth from t_ns on, aligned on those frames
// alone (-1: fewer than three estimates there).
double Ate(const Simulation& sim, const testing::SimReplay& run, int64_t t_ns) {
  double ate = -1.0;
  testing::AteFrom(sim, run.outputs, t_ns, &ate);
  return ate;
}

// The in-motion run's start: its first window's scale error (the spread of
// its positions against the truth's, minus 1; test/testing/spread.h).
double StartScaleError(const Simulation& sim, const StartRecord& start) {
  std::vector<Eigen::Vector3d> est, truth;
  for (const InitialFrame& f : start.window) {
    est.push_back(f.p_w_b);
    const auto it = std::lower_bound(
        sim.ground_truth.begin(), sim.ground_truth.end(), f.t_imu_ns,
        [](const StampedState& x, int64_t t) { return x.t_ns < t; });
    truth.push_back(it == sim.ground_truth.end() ? sim.ground_truth.back().p_w_b
                                                 : it->p_w_b);
  }
  return testing::Spread(est) / testing::Spread(truth) - 1.0;
}

// The truth at t_ns (the first state at or after it; the last one past the
// end).
const StampedState& TruthNear(const Simulation& sim, int64_t t_ns) {
  const auto it = std::lower_bound(
      sim.ground_truth.begin(), sim.ground_truth.end(), t_ns,
      [](const StampedState& x, int64_t t) { return x.t_ns < t; });
  return it == sim.ground_truth.end() ? sim.ground_truth.back() : *it;
}

// The angle between the estimated and the true world z seen from the body
// [deg]: the tilt error, whatever the yaw.
double TiltErrorDeg(const Eigen::Quaterniond& q_est,
                    const Eigen::Quaterniond& q_true) {
  const Eigen::Vector3d z_est = q_est.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  return std::atan2(z_est.cross(z_true).norm(), z_est.dot(z_true)) * 180.0 /
         M_PI;
}

// --verbose: both runs' tilt error [deg] and accelerometer-bias error
// [m/s^2] at the first estimate at or after t_ns ("-" where there is none).
void PrintStateErrors(const Simulation& sim, const testing::SimReplay& moving,
                      const testing::SimReplay& rest, int64_t t_ns,
                      double after_s) {
  auto at = [&](const testing::SimReplay& run) -> const EstimatorOutput* {
    for (const EstimatorOutput& o : run.outputs) {
      if (o.processed && o.initialized && o.t_ns >= t_ns) return &o;
    }
    return nullptr;
  };
  const EstimatorOutput* m = at(moving);
  const EstimatorOutput* r = at(rest);
  if (m == nullptr || r == nullptr) return;
  const StampedState& gm = TruthNear(sim, m->t_ns);
  const StampedState& gr = TruthNear(sim, r->t_ns);
  std::printf(
      "    state at t0 + %.1f s: tilt in motion %.3f deg, from rest %.3f deg; "
      "|b_a error| in motion %.4f, from rest %.4f m/s^2; |b_g error| in "
      "motion %.5f, from rest %.5f rad/s\n",
      after_s, TiltErrorDeg(m->q_w_b, gm.q_w_b), TiltErrorDeg(r->q_w_b, gr.q_w_b),
      (m->b_a - gm.b_a).norm(), (r->b_a - gr.b_a).norm(),
      (m->b_g - gm.b_g).norm(), (r->b_g - gr.b_g).norm());
}

// One window of the comparison (the common frames, or from t0 + S): both
// runs' ATEs and their ratio per run.
struct Comparison {
  std::string name;
  Distribution moving, rest, ratio;
  int within = 0;  // runs whose in-motion ATE is within 20 % of from rest
  void Add(double ate_moving, double ate_rest) {
    if (ate_moving < 0.0 || ate_rest < 0.0) return;
    moving.Add(ate_moving);
    rest.Add(ate_rest);
    ratio.Add(ate_moving / ate_rest);
    within += ate_moving <= 1.2 * ate_rest ? 1 : 0;
  }
  void Print(int runs) const {
    std::printf(
        "  %s: in motion %s; from rest %s\n    ratio in motion / from rest: "
        "median %.3f, min %.3f, max %.3f; within 20 %%: %d of %d runs\n",
        name.c_str(), moving.Describe(1.0, "m").c_str(),
        rest.Describe(1.0, "m").c_str(), ratio.Quantile(0.5),
        ratio.Quantile(0.0), ratio.Quantile(1.0), within, runs);
  }
};

}  // namespace

void SameSequenceAte(const std::string& preset, const Args& args) {
  const SimulatorOptions base = LoadPreset(preset);
  const int runs = std::min(args.seeds, args.ate_runs);
  std::vector<Comparison> windows(1 + args.ate_from_s.size());
  windows[0].name = "common frames (from the in-motion run's first estimate)";
  for (size_t i = 0; i < args.ate_from_s.size(); ++i) {
    char b[64];
    std::snprintf(b, sizeof(b), "from t0 + %.1f s", args.ate_from_s[i]);
    windows[1 + i].name = b;
  }
  Distribution start_after_cut, start_scale;
  int no_start = 0;
  for (int k = 0; k < runs; ++k) {
    if (!args.ate_run_only.empty() &&
        std::find(args.ate_run_only.begin(), args.ate_run_only.end(), k) ==
            args.ate_run_only.end()) {
      continue;
    }
    SimulatorOptions r = RunOptions(base, k, runs);
    r.motion.still_duration_s = 2.0;
    r.motion.blend_duration_s = 2.0;
    // After the blend (4 s), a different moment of each run's lap.
    const double t0_s = args.cut_s > 0.0 ? args.cut_s : 5.0 + 1.5 * (k % 4);
    r.duration_s = t0_s + base.duration_s;  // the in-motion run: the preset's
    const Simulation sim = Simulate(r);
    const int64_t t0_ns = sim.imu.front().t_ns + std::llround(t0_s * 1e9);
    const testing::SimReplay rest =
        testing::ReplaySimulation(sim, OptionsOf(r, args));
    const Simulation cut = testing::CutSimulation(sim, t0_ns);
    const testing::SimReplay moving =
        testing::ReplaySimulation(cut, OptionsOf(r, args));
    const int64_t first = FirstEstimate(moving.outputs);
    std::printf("  %s seed %u phase %.2f s, cut at %.2f s: ", preset.c_str(),
                r.seed, r.motion.start_phase_s, t0_s);
    if (first == INT64_MAX) {
      ++no_start;
      std::printf("no start in motion\n");
      continue;
    }
    const double after_s = 1e-9 * static_cast<double>(first - t0_ns);
    start_after_cut.Add(after_s);
    const double a = Ate(sim, moving, first), b = Ate(sim, rest, first);
    windows[0].Add(a, b);
    const StartRecord& start = moving.summary.starts.front();
    const double scale = StartScaleError(sim, start);
    start_scale.Add(std::abs(scale));
    std::printf(
        "start %.2f s after the cut (%s, scale %+.1f %%); common frames: ATE "
        "in motion %.4f m, from rest %.4f m, ratio %.3f; resets %lld / "
        "%lld\n",
        after_s, InitMethodName(start.method), 100.0 * scale, a, b, a / b,
        static_cast<long long>(moving.summary.resets),
        static_cast<long long>(rest.summary.resets));
    for (const RealignmentRecord& re : moving.summary.realignments) {
      std::printf(
          "    realignment %.2f s after the cut: scale x %.3f (std %.1f %%, "
          "%d frames), %s\n",
          1e-9 * static_cast<double>(re.t_ns - t0_ns), re.result.scale,
          100.0 * re.result.scale_sigma, re.result.common_frames,
          re.applied ? "applied" : "not applied");
    }
    if (args.verbose) {
      for (const double s : {0.0, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0}) {
        PrintStateErrors(sim, moving, rest, t0_ns + std::llround(s * 1e9), s);
      }
    }
    for (size_t i = 0; i < args.ate_from_s.size(); ++i) {
      const int64_t from = t0_ns + std::llround(args.ate_from_s[i] * 1e9);
      const double ai = Ate(sim, moving, from), bi = Ate(sim, rest, from);
      windows[1 + i].Add(ai, bi);
      std::printf(
          "    from t0 + %.1f s: in motion %.4f m, from rest %.4f m, "
          "ratio %.3f\n",
          args.ate_from_s[i], ai, bi, ai / bi);
    }
  }
  std::printf(
      "%s, the same sequence from rest and cut in motion, %d runs (%.0f s "
      "after the cut): %d without a start in motion; start after the cut "
      "%s; |start scale error| %s\n",
      preset.c_str(), runs, base.duration_s, no_start,
      start_after_cut.Describe(1.0, "s").c_str(),
      start_scale.Describe(100.0, "%").c_str());
  for (const Comparison& w : windows) w.Print(runs);
}

void SeparateSimulationsAte(const std::string& preset, const Args& args) {
  const SimulatorOptions base = LoadPreset(preset);
  const int runs = std::min(args.seeds, args.ate_runs);
  Distribution moving, rest;
  std::vector<Distribution> moving_from(args.ate_from_s.size()),
      rest_from(args.ate_from_s.size());
  for (int k = 0; k < runs; ++k) {
    const SimulatorOptions o = RunOptions(base, k, runs);
    const Simulation sim_a = Simulate(o);
    const testing::SimReplay a =
        testing::ReplaySimulation(sim_a, OptionsOf(o, args));
    // The same motion from rest: a 2 s still start blending into it.
    SimulatorOptions r = o;
    r.motion.still_duration_s = 2.0;
    r.motion.blend_duration_s = 2.0;
    const Simulation sim_b = Simulate(r);
    const testing::SimReplay b =
        testing::ReplaySimulation(sim_b, OptionsOf(r, args));
    moving.Add(a.ate_rmse_m);
    rest.Add(b.ate_rmse_m);
    for (size_t i = 0; i < args.ate_from_s.size(); ++i) {
      const int64_t from_ns = std::llround(args.ate_from_s[i] * 1e9);
      const double ate_a =
          Ate(sim_a, a, sim_a.ground_truth.front().t_ns + from_ns);
      const double ate_b =
          Ate(sim_b, b, sim_b.ground_truth.front().t_ns + from_ns);
      moving_from[i].Add(ate_a);
      rest_from[i].Add(ate_b);
      std::printf(
          "    from %.1f s on: ATE in motion %.4f m, from rest %.4f m\n",
          args.ate_from_s[i], ate_a, ate_b);
    }
    if (args.against_default) {
      const Simulation sim = Simulate(o);
      const testing::SimReplay d =
          testing::ReplaySimulation(sim, testing::OptionsFor(o));
      const int64_t t0 = sim.ground_truth.front().t_ns;
      auto first_start = [&](const testing::SimReplay& s) {
        return s.summary.starts.empty() ? INT64_MAX
                                        : s.summary.starts.front().t_ns;
      };
      const int64_t common = std::max(first_start(a), first_start(d));
      const double ate_a = Ate(sim, a, common), ate_d = Ate(sim, d, common);
      std::printf(
          "    against the default options: start %.2f s (default %.2f s), "
          "ATE whole run %.4f m (default %.4f m, ratio %.3f), on the frames "
          "both estimate %.4f m (default %.4f m, ratio %.3f)\n",
          1e-9 * static_cast<double>(first_start(a) - t0),
          1e-9 * static_cast<double>(first_start(d) - t0), a.ate_rmse_m,
          d.ate_rmse_m, a.ate_rmse_m / d.ate_rmse_m, ate_a, ate_d,
          ate_a / ate_d);
    }
    std::printf(
        "  %s seed %u: ATE in motion %.4f m (resets %lld), from rest "
        "%.4f m (resets %lld)\n",
        preset.c_str(), o.seed, a.ate_rmse_m,
        static_cast<long long>(a.summary.resets), b.ate_rmse_m,
        static_cast<long long>(b.summary.resets));
  }
  std::printf(
      "%s ATE over %d runs of %.0f s (two simulations): in motion %s; from "
      "rest %s\n",
      preset.c_str(), runs, base.duration_s, moving.Describe(1.0, "m").c_str(),
      rest.Describe(1.0, "m").c_str());
  for (size_t i = 0; i < args.ate_from_s.size(); ++i) {
    std::printf("  from %.1f s on: in motion %s; from rest %s\n",
                args.ate_from_s[i], moving_from[i].Describe(1.0, "m").c_str(),
                rest_from[i].Describe(1.0, "m").c_str());
  }
}

}  // namespace vio
