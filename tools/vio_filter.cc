// vio_filter: the notes' linear Kalman filter (navigation/pose_filter.h) over
// a trajectory: a smooth pose to steer by, optionally predicted ahead to
// make up for the latency between the estimate and the controller.

#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset/trajectory_io.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "navigation/navigation_plot.h"
#include "navigation/pose_filter.h"
#include "tools/command_line.h"

namespace {

using namespace vio;  // NOLINT(build/namespaces): a tool's main file

constexpr char kUsage[] =
    "usage: vio_filter IN.tum --out OUT.tum --position-noise S --accel-noise "
    "K\n"
    "                  [--yaw-noise R] [--yaw-accel-noise K3] [--predict-ms "
    "D]\n"
    "                  [--ground-truth GT] [--plot FILE.png]\n"
    "\n"
    "Filters the poses of IN (TUM, e.g. vio_replay's trajectory.tum, or an\n"
    "EuRoC ground-truth / state CSV) with the notes' linear Kalman filter on\n"
    "x, y, z and yaw (each with its rate, white-acceleration model) and "
    "writes\n"
    "OUT.tum at the same stamps: filtered position and yaw, roll and pitch as\n"
    "given. With --predict-ms D every output pose is the state predicted D ms\n"
    "past its input pose and is stamped t + D (latency compensation).\n"
    "\n"
    "  --position-noise S   sigma of the input positions [m]\n"
    "  --accel-noise K      white acceleration driving x, y, z [m/s^2]\n"
    "  --yaw-noise R        sigma of the input yaw [rad] (default 0.02)\n"
    "  --yaw-accel-noise K3 white angular acceleration of yaw [rad/s^2]\n"
    "                       (default 1)\n"
    "  --predict-ms D       predict D >= 0 ms ahead (default 0)\n"
    "  --ground-truth GT    also compare with GT (TUM or EuRoC CSV): the "
    "input\n"
    "                       is aligned to it (posyaw), the same alignment is\n"
    "                       applied to the output; prints position errors\n"
    "  --plot FILE.png      the picture (default: OUT with .png)\n";

struct Args {
  std::string in, out, ground_truth, plot;
  PoseFilterOptions filter;
  double predict_ms = 0.0;
  bool have_position_noise = false, have_accel_noise = false;
  bool help = false;
};

Args ParseArgs(int argc, char** argv) {
  Args args;
  CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--help" || a == "-h") {
      args.help = true;
      return args;
    } else if (a == "--out") {
      args.out = line.Value();
    } else if (a == "--position-noise") {
      args.filter.position_noise_m = line.Number<double>();
      args.have_position_noise = true;
    } else if (a == "--accel-noise") {
      args.filter.accel_noise_m_s2 = line.Number<double>();
      args.have_accel_noise = true;
    } else if (a == "--yaw-noise") {
      args.filter.yaw_noise_rad = line.Number<double>();
    } else if (a == "--yaw-accel-noise") {
      args.filter.yaw_accel_noise_rad_s2 = line.Number<double>();
    } else if (a == "--predict-ms") {
      args.predict_ms = line.Number<double>();
    } else if (a == "--ground-truth") {
      args.ground_truth = line.Value();
    } else if (a == "--plot") {
      args.plot = line.Value();
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    } else if (args.in.empty()) {
      args.in = a;
    } else {
      throw std::invalid_argument("more than one input (" + args.in + ", " + a +
                                  ")");
    }
  }
  if (args.in.empty() || args.out.empty() || !args.have_position_noise ||
      !args.have_accel_noise) {
    throw std::invalid_argument(
        "IN, --out, --position-noise and --accel-noise are required\n" +
        std::string(kUsage));
  }
  if (!(args.predict_ms >= 0.0) || !std::isfinite(args.predict_ms)) {
    throw std::invalid_argument("--predict-ms must be >= 0");
  }
  args.filter.Validate();
  if (args.plot.empty()) {
    const size_t dot = args.out.find_last_of('.');
    const size_t slash = args.out.find_last_of('/');
    const bool ext =
        dot != std::string::npos && (slash == std::string::npos || dot > slash);
    args.plot = (ext ? args.out.substr(0, dot) : args.out) + ".png";
  }
  return args;
}

struct Filtered {
  Trajectory output;  // what OUT.tum holds
  Trajectory held;    // the input pose at each output stamp (no prediction)
  double nis_mean = 0.0;
};

Filtered Run(const Trajectory& input, const Args& args) {
  PoseFilter filter(args.filter);
  const double ahead_s = 1e-3 * args.predict_ms;
  Filtered r;
  double nis_sum = 0.0;
  for (size_t i = 0; i < input.size(); ++i) {
    const StampedPose& in = input[i];
    FilteredPose f = filter.Add({in.t_ns, in.p_w_b, YawOf(in.q_w_b)});
    if (i > 0) nis_sum += f.nis;
    if (ahead_s > 0.0) f = filter.PredictAhead(ahead_s);
    r.output.push_back({f.t_ns, f.p_w, WithYaw(in.q_w_b, f.yaw_rad)});
    r.held.push_back({f.t_ns, in.p_w_b, in.q_w_b});
  }
  r.nis_mean = input.size() > 1 ? nis_sum / (input.size() - 1) : 0.0;
  return r;
}

double Seconds(int64_t t_ns, int64_t t0_ns) { return 1e-9 * (t_ns - t0_ns); }

// Position errors [m] of each pose of `poses` (in the estimate's world,
// mapped by `align`) against the truth nearest its stamp (within 10 ms);
// poses without truth are skipped. Returns (t, error) points and the RMSE.
double Errors(const Trajectory& poses, const Trajectory& truth,
              const Alignment& align, int64_t t0_ns,
              std::vector<Eigen::Vector2d>* curve) {
  const Association a = Associate(poses, truth);
  if (a.size() == 0) throw std::runtime_error("no pose within 10 ms of truth");
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double e =
        (align.Apply(a.estimate[i]).p_w_b - a.ground_truth[i].p_w_b).norm();
    sum += e * e;
    if (curve) curve->push_back({Seconds(a.estimate[i].t_ns, t0_ns), e});
  }
  return std::sqrt(sum / a.size());
}

std::vector<Eigen::Vector2d> TopView(const Trajectory& t,
                                     const Alignment& align) {
  std::vector<Eigen::Vector2d> xy;
  for (const StampedPose& p : t) xy.push_back(align.Apply(p).p_w_b.head<2>());
  return xy;
}

int Main(const Args& args) {
  if (args.help) {
    std::printf("%s", kUsage);
    return 0;
  }
  const Trajectory input = ReadTrajectory(args.in);
  std::printf(
      "input %s: %zu poses over %.2f s\n"
      "filter: position noise %g m, accel noise %g m/s^2, yaw noise %g rad, "
      "yaw accel noise %g rad/s^2, predict %g ms\n",
      args.in.c_str(), input.size(),
      Seconds(input.back().t_ns, input.front().t_ns),
      args.filter.position_noise_m, args.filter.accel_noise_m_s2,
      args.filter.yaw_noise_rad, args.filter.yaw_accel_noise_rad_s2,
      args.predict_ms);
  const Filtered f = Run(input, args);
  WriteTum(args.out, f.output);
  std::printf("wrote %s (%zu poses)\n", args.out.c_str(), f.output.size());
  std::printf("NIS mean %.3f (4 expected when the noises fit the input)\n",
              f.nis_mean);

  const int64_t t0 = input.front().t_ns;
  Alignment align;  // identity without ground truth
  std::vector<PlotCurve> top = {{"input", TopView(input, align), 0, 0},
                                {args.predict_ms > 0 ? "predicted" : "filtered",
                                 TopView(f.output, align), 1, 1}};
  std::vector<PlotCurve> bottom;
  std::string y_label;
  if (!args.ground_truth.empty()) {
    const Trajectory truth = ReadTrajectory(args.ground_truth);
    const Association a = Associate(input, truth);
    if (a.size() < MinimumPoses(AlignmentMode::kPosYaw)) {
      throw std::runtime_error(args.ground_truth +
                               ": too few poses within 10 ms of the input");
    }
    align = Align(a.estimate, a.ground_truth, AlignmentMode::kPosYaw);
    PlotCurve in{"input", {}, 0, 1}, out{"", {}, 1, 1};
    const double e_in = Errors(input, truth, align, t0, &in.points);
    const double e_out = Errors(f.output, truth, align, t0, &out.points);
    std::printf(
        "position error rmse (posyaw aligned): input %.4f m, %s %.4f m\n", e_in,
        args.predict_ms > 0 ? "predicted" : "filtered", e_out);
    if (args.predict_ms > 0) {
      PlotCurve held{"holding the last pose", {}, 2, 1};
      const double e_held = Errors(f.held, truth, align, t0, &held.points);
      std::printf(
          "%g ms ahead: prediction rmse %.4f m, holding the last pose %.4f m "
          "(ratio %.2f)\n",
          args.predict_ms, e_out, e_held, e_out / e_held);
      bottom.push_back(held);
    } else {
      bottom.push_back(in);
    }
    out.label = args.predict_ms > 0 ? "predicted" : "filtered";
    bottom.push_back(out);
    y_label = "position error vs ground truth at the output stamp [m]";
    top = {{"ground truth", TopView(truth, Alignment()), 3, 3},
           {"input (aligned)", TopView(input, align), 0, 0},
           {top[1].label + " (aligned)", TopView(f.output, align), 1, 1}};
  } else {
    PlotCurve d{"|output - input|", {}, 1, 1};
    for (size_t i = 0; i < input.size(); ++i) {
      d.points.push_back({Seconds(input[i].t_ns, t0),
                          (f.output[i].p_w_b - input[i].p_w_b).norm()});
    }
    bottom.push_back(d);
    y_label = "distance of the output from the input [m]";
  }
  WriteFilterPlot(args.plot, "vio_filter: " + args.in, top, y_label, bottom);
  std::printf("plot %s\n", args.plot.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(ParseArgs(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
