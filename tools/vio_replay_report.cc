#include "tools/vio_replay_report.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "dataset/trajectory_io.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "eval/plot.h"

namespace vio {
namespace {

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

LandmarkStream::LandmarkStream(const std::string& dir)
    : path_((std::filesystem::path(dir) / "landmarks.csv").string()),
      writer_(path_) {}

void LandmarkStream::Take(Estimator* estimator) {
  for (const auto& [id, m] : estimator->TakeFinishedLandmarks()) {
    writer_.Write({m.p_w, m.parallax_deg});
  }
}

void LandmarkStream::Finish(Estimator* estimator) {
  Take(estimator);
  for (const auto& [id, m] : estimator->MappedLandmarks()) {
    writer_.Write({m.p_w, m.parallax_deg});
  }
  writer_.Close();
  std::printf("wrote %s (%lld landmarks)\n", path_.c_str(),
              static_cast<long long>(writer_.rows()));
}

Progress::Progress(size_t total, int64_t first_ns)
    : total_(total),
      first_ns_(first_ns),
      terminal_(isatty(fileno(stdout)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void Progress::Update(size_t i, int64_t t_ns) {
  const auto now = std::chrono::steady_clock::now();
  const double percent = 100.0 * (i + 1) / std::max<size_t>(1, total_);
  const double wall = std::max(1e-9, Seconds(now - start_));
  const double rt = 1e-9 * static_cast<double>(t_ns - first_ns_) / wall;
  if (terminal_) {
    if (Seconds(now - last_draw_) < 0.1 && i + 1 < total_) return;
    last_draw_ = now;
    const int width = 30;
    const int filled = static_cast<int>(percent / 100.0 * width);
    std::printf("\r[%s%s] %zu/%zu frames %5.1f %%  %.1fx real time",
                std::string(filled, '#').c_str(),
                std::string(width - filled, '.').c_str(), i + 1, total_,
                percent, rt);
    std::fflush(stdout);
    return;
  }
  const int decile = static_cast<int>(percent / 10.0);
  if (decile == last_decile_) return;
  last_decile_ = decile;
  std::printf("progress: %zu/%zu frames (%.0f %%), %.1fx real time\n", i + 1,
              total_, percent, rt);
}

void Progress::Finish() {
  if (terminal_) std::printf("\n");
}

Trajectory WriteOutputs(const std::string& dir,
                        const std::vector<EstimatorOutput>& outputs) {
  Trajectory poses;
  std::vector<StampedState> states;
  for (const EstimatorOutput& o : outputs) {
    if (!o.processed || !o.initialized) continue;
    poses.push_back({o.t_ns, o.p_w_b, o.q_w_b});
    states.push_back({o.t_ns, o.p_w_b, o.q_w_b, o.v_w, o.b_a, o.b_g});
  }
  const std::filesystem::path d(dir);
  WriteTum((d / "trajectory.tum").string(), poses);
  WriteStateCsv((d / "states.csv").string(), states);
  std::printf("wrote %s and %s (%zu poses)\n",
              (d / "trajectory.tum").string().c_str(),
              (d / "states.csv").string().c_str(), poses.size());
  return poses;
}

void PrintSummary(const EstimatorSummary& s,
                  const std::vector<EstimatorOutput>& outputs, double wall_s) {
  const double span_s =
      outputs.size() < 2
          ? 0.0
          : 1e-9 * static_cast<double>(outputs.back().t_ns - outputs[0].t_ns);
  std::printf("summary\n");
  std::printf(
      "  frames      %lld (processed %lld, before init %lld, skipped "
      "%lld)\n",
      (long long)s.frames, (long long)s.frames_processed,
      (long long)s.frames_before_init,
      (long long)(s.frames_out_of_order + s.frames_without_imu));
  std::printf("  keyframes   %lld\n", (long long)s.keyframes);
  std::printf("  resets      %lld\n", (long long)s.resets);
  if (s.imu_noise_updates > 0) {
    std::printf(
        "  imu noise   white-noise scale accelerometer %.3f, gyroscope %.3f "
        "(adapted over %lld steps)\n",
        s.imu_noise_scale_accelerometer, s.imu_noise_scale_gyroscope,
        (long long)s.imu_noise_updates);
  }
  for (const ResetEvent& e : s.reset_log) {
    std::printf("    at %lld ns: %s\n", (long long)e.t_ns,
                FailureName(e.reason));
  }
  std::printf(
      "  solver time per step  median %.2f ms, p95 %.2f ms, max %.2f "
      "ms CPU (%zu steps; wall median %.2f ms)\n",
      1e3 * s.solver_cpu_time_s.Quantile(0.5),
      1e3 * s.solver_cpu_time_s.Quantile(0.95),
      1e3 * s.solver_cpu_time_s.Quantile(1.0),
      static_cast<size_t>(s.solver_cpu_time_s.count()),
      1e3 * s.solver_time_s.Quantile(0.5));
  std::printf(
      "  solver time split     Jacobians %.2f s, residuals %.2f s, linear "
      "solver %.2f s, preprocessing %.2f s; %.1f iterations per step\n",
      s.solver_jacobian_time_s, s.solver_residual_time_s,
      s.solver_linear_time_s, s.solver_preprocess_time_s,
      s.solver_time_s.empty()
          ? 0.0
          : static_cast<double>(s.solver_iterations) /
                static_cast<double>(s.solver_time_s.count()));
  std::printf(
      "  solver work per step  median %.0f window frames, %.0f residuals\n",
      s.window_frames_per_step.Quantile(0.5),
      s.residuals_per_step.Quantile(0.5));
  std::printf(
      "  marginalisation       median %.2f ms, max %.2f ms CPU (%lld, "
      "%lld failed, %lld releases of world points, %lld world points "
      "capped, at most %lld held)\n",
      1e3 * s.marginalization_cpu_time_s.Quantile(0.5),
      1e3 * s.marginalization_cpu_time_s.Quantile(1.0),
      (long long)s.marginalizations, (long long)s.marginalization_failures,
      (long long)s.points_released, (long long)s.points_capped,
      (long long)s.most_world_points);
  std::printf(
      "  prior square root     %lld Cholesky, %lld floored block by block, "
      "%lld by subspace iteration, %lld eigen\n",
      (long long)s.prior_cholesky, (long long)s.prior_block_floor,
      (long long)s.prior_subspace_floor, (long long)s.prior_eigen);
  std::printf(
      "  landmarks per step    median %.0f; outliers removed: %lld "
      "sightings, %lld landmarks; %lld landmarks behind their anchor "
      "removed\n",
      s.landmarks_per_step.Quantile(0.5),
      (long long)s.outlier_sightings_removed,
      (long long)s.outlier_landmarks_removed,
      (long long)s.landmarks_behind_removed);
  std::printf(
      "  skipped input         imu non-finite %lld, imu out of order "
      "%lld, observations %lld, frames without observations %lld\n",
      (long long)s.imu_non_finite, (long long)s.imu_out_of_order,
      (long long)s.observations_skipped,
      (long long)s.frames_without_observations);
  std::printf("  wall time   %.2f s for %.2f s of data: %.1fx real time\n",
              wall_s, span_s, wall_s > 0 ? span_s / wall_s : 0.0);
}

void PrintStarts(const EstimatorSummary& s) {
  for (const StartRecord& r : s.starts) {
    std::printf("  start       %s%s at %lld ns", InitMethodName(r.method),
                r.restart ? " (re-initialisation after a reset)" : "",
                static_cast<long long>(r.t_ns));
    if (r.method != InitMethod::kStatic) {
      const InitDiagnostics& d = r.diagnostics;
      std::printf(": %zu frames, IMU excitation %.2f m/s^2, ", r.window.size(),
                  d.imu_excitation);
      if (ScaleChangeDefined(d)) {
        std::printf("joint adjustment moved the scale %+.1f %%",
                    100.0 * d.refine_scale_change);
      } else if (d.refined_path_m < kMinScalePathM) {
        // At rest the path is position noise (estimator/initial_window.h).
        std::printf(
            "joint adjustment's scale change not meaningful (the window's "
            "path, %.1f mm, is too short to define a scale: at rest it is "
            "position noise)",
            1e3 * d.refined_path_m);
      } else if (d.refined_scale_sigma >= 0.0) {
        std::printf(
            "joint adjustment's scale change not meaningful (the window's "
            "path, %.1f mm, defines no scale: its spread's std is %.0f %% "
            "of it)",
            1e3 * d.refined_path_m, 100.0 * d.refined_scale_sigma);
      } else {
        std::printf(
            "joint adjustment's scale change not meaningful (the window's "
            "path, %.1f mm, has no computable uncertainty)",
            1e3 * d.refined_path_m);
      }
    }
    std::printf("\n");
  }
  if (!s.init_attempts.empty()) {
    std::printf("  start attempts refused  %zu: %s\n", s.init_attempts.size(),
                DescribeInitFailures(s.init_attempts).c_str());
  }
  std::printf("  zero velocity         %lld frames held still\n",
              static_cast<long long>(s.zero_velocity_frames));
}

std::vector<StampedState> GroundTruthAt(const std::string& path,
                                        const Trajectory& estimate) {
  NearestGroundTruth nearest(estimate);
  ForEachEurocGroundTruth(path, [&](const StampedState& s) { nearest.Add(s); });
  if (static_cast<size_t>(nearest.states()) < estimate.size()) {
    return ReadEurocGroundTruth(path);
  }
  return nearest.Take();
}

void Evaluate(const std::string& dir, const Trajectory& estimate,
              const std::vector<StampedState>& ground_truth, size_t frames) {
  Trajectory truth;
  for (const StampedState& s : ground_truth) truth.push_back(PoseOf(s));
  const Association a = Associate(estimate, truth);
  if (a.size() < 2) {
    // No alignment from fewer than two poses; the exit status says why.
    std::printf(
        "  ATE (posyaw)  n/a (%zu of %zu frames with a pose at a "
        "ground-truth stamp)\n",
        a.size(), frames);
    return;
  }
  const Alignment alignment =
      Align(a.estimate, a.ground_truth, AlignmentMode::kPosYaw);
  const Trajectory aligned = alignment.Apply(a.estimate);
  const AbsoluteTrajectoryError ate = ComputeAte(aligned, a.ground_truth);
  const RelativePoseError rpe =
      ComputeRpe(aligned, a.ground_truth, 1.0, RpeUnit::kMeters);
  std::printf(
      "  ATE (posyaw)  rmse %.4f m, max %.4f m, rotation rmse %.3f "
      "deg (%zu of %zu frames%s)\n",
      ate.translation.rmse, ate.translation.max, ate.rotation.rmse, a.size(),
      frames,
      alignment.yaw_from_orientations
          ? "; still ground truth: yaw aligned from orientations"
          : "");
  if (rpe.pairs.empty()) {
    std::printf("  RPE (1 m)     n/a (no two poses 1 m of travel apart)\n");
  } else {
    std::printf(
        "  RPE (1 m)     rmse %.4f m, rotation rmse %.3f deg (%zu "
        "pairs)\n",
        rpe.translation.rmse, rpe.rotation.rmse, rpe.pairs.size());
  }
  const std::string plot =
      (std::filesystem::path(dir) / "evaluation.png").string();
  PlotOptions options;
  options.title = "vio_replay: posyaw-aligned estimate";
  WriteEvaluationPlot(plot, a.ground_truth, aligned, ate.translation_m,
                      options);
  std::printf("wrote %s\n", plot.c_str());
}

}  // namespace vio
