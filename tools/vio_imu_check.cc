// vio_imu_check: how a sequence's recorded IMU agrees with the curve that
// vio_sim --flight fits to its ground truth (dataset/imu_curve_residual.h):
// the time offset that best aligns each sensor with the curve, the residual's
// rms per axis, and its Allan deviation as an equivalent white-noise density
// next to the density the estimator assumes. docs/recorded_flights.md.

#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/recorded_flight.h"
#include "dataset/imu_curve_fit.h"
#include "dataset/imu_curve_residual.h"
#include "dataset/trajectory_curve.h"
#include "tools/command_line.h"
#include "tools/curve_flags.h"

namespace {

struct Args {
  std::string flight;
  std::string ground_truth;  // empty: the folder's own
  double knot_spacing_s = vio::CurveFitOptions().knot_spacing_s;
  double rotation_knot_spacing_s = 0.0;  // 0: knot_spacing_s
  double max_offset_s = vio::ImuCurveResidualOptions().max_offset_s;
  double offset_s = 0.0;  // applied to the ground truth before the fit
  vio::FlightCurve curve = vio::FlightCurve::kGroundTruth;  // --curve
  vio::ImuCurveFitOptions imu_curve;
  bool help = false;
};

constexpr char kUsage[] =
    "usage: vio_imu_check FOLDER [--ground-truth FILE] [--knot-spacing S]\n"
    "                     [--rotation-knot-spacing S] [--max-offset S]\n"
    "                     [--offset S] [--curve ground-truth|imu]\n"
    "                     [--fit-noise-scale S] [--fit-bias-walk-scale S]\n"
    "                     [--fit-bias-knot-spacing S]\n"
    "\n"
    "Fits vio_sim --flight's curve to FOLDER's ground truth and compares the\n"
    "recorded IMU (mav0/imu0/data.csv) with the curve's body rate and\n"
    "specific force: the time offset d that best aligns each sensor (the IMU\n"
    "sample stamped t saw the motion the ground truth stamps t + d), the\n"
    "residual's rms per axis (5 s moving average, the bias, removed) and its\n"
    "Allan deviation as an equivalent white-noise density.\n"
    "\n"
    "  --ground-truth FILE  EuRoC CSV or TUM (default: the folder's)\n"
    "  --knot-spacing S     of the fitted B-spline [s] (default 0.05)\n"
    "  --rotation-knot-spacing S  of its rotations (default 0: the same)\n"
    "  --max-offset S       offsets searched in [-S, S] (default 0.05)\n"
    "  --offset S           compare with the ground truth's stamps moved by\n"
    "                       -S, to see what correcting an offset would do\n"
    "                       (default 0)\n"
    "  --curve imu          compare with vio_sim --curve imu's curve, fitted\n"
    "                       to the ground truth and the recorded IMU together\n"
    "                       (dataset/imu_curve_fit.h), the fitted biases\n"
    "                       removed from the samples first (default\n"
    "                       ground-truth: the ground truth's curve alone)\n"
    "  --fit-noise-scale S, --fit-bias-walk-scale S,\n"
    "  --fit-bias-knot-spacing S, --fit-position-sigma M,\n"
    "  --fit-rotation-sigma RAD, --fit-knot-spacing S\n"
    "                       the joint fit's options, as vio_sim's\n";

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string flag = line.Current();
    if (flag == "--ground-truth") {
      args.ground_truth = line.Value();
    } else if (flag == "--knot-spacing") {
      args.knot_spacing_s = line.Number<double>();
    } else if (flag == "--rotation-knot-spacing") {
      args.rotation_knot_spacing_s = line.Number<double>();
    } else if (flag == "--max-offset") {
      args.max_offset_s = line.Number<double>();
    } else if (flag == "--offset") {
      args.offset_s = line.Number<double>();
    } else if (vio::ParseCurveFlag(line, &args.curve, &args.imu_curve)) {
      // --curve, --fit-*: tools/curve_flags.h
    } else if (flag == "--help" || flag == "-h") {
      args.help = true;
    } else if (!flag.empty() && flag[0] != '-' && args.flight.empty()) {
      args.flight = flag;
    } else {
      throw std::invalid_argument("unknown argument '" + flag + "'\n" + kUsage);
    }
  }
  if (!args.help && args.flight.empty()) {
    throw std::invalid_argument(std::string("no FOLDER given\n") + kUsage);
  }
  if (!(args.knot_spacing_s > 0.0) || !(args.max_offset_s > 0.0) ||
      !(args.rotation_knot_spacing_s >= 0.0) ||
      !std::isfinite(args.offset_s)) {
    throw std::invalid_argument(
        "--knot-spacing and --max-offset expect seconds > 0, "
        "--rotation-knot-spacing seconds >= 0");
  }
  return args;
}

void PrintAxes(const char* what, const Eigen::Vector3d& v, double scale) {
  std::printf("| %s | %.4g | %.4g | %.4g |\n", what, v.x() * scale,
              v.y() * scale, v.z() * scale);
}

void PrintJointFit(const vio::ImuCurveFitReport& j,
                   const vio::ImuCurveFitOptions& o) {
  std::printf(
      "joint fit (ground truth and IMU): %d control points every %.4f s, "
      "bias knots every %.2f s, %d poses, %d IMU samples, %d Gauss-Newton "
      "steps\n"
      "  through the ground truth: position rms %.3f mm max %.2f mm, rotation "
      "rms %.3f mrad max %.2f mrad\n"
      "  IMU residual rms x, y, z: gyroscope %.3f, %.3f, %.3f mrad/s, "
      "accelerometer %.4f, %.4f, %.4f m/s^2\n",
      j.control_points, o.knot_spacing_s, o.bias_knot_spacing_s, j.poses,
      j.imu_samples, j.iterations, 1e3 * j.position_rms_m,
      1e3 * j.position_max_m, 1e3 * j.rotation_rms_rad,
      1e3 * j.rotation_max_rad, 1e3 * j.gyroscope_rms.x(),
      1e3 * j.gyroscope_rms.y(), 1e3 * j.gyroscope_rms.z(),
      j.accelerometer_rms.x(), j.accelerometer_rms.y(),
      j.accelerometer_rms.z());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::cout << kUsage;
      return 0;
    }
    const vio::RecordedFlight flight =
        vio::LoadRecordedFlight(args.flight, args.ground_truth);
    if (flight.imu.empty()) {
      throw std::invalid_argument(args.flight +
                                  ": no IMU recording (mav0/imu0/data.csv)");
    }
    const auto shift_ns = static_cast<int64_t>(std::llround(args.offset_s * 1e9));
    std::vector<vio::StampedPose> poses;
    for (const vio::StampedState& s : flight.ground_truth) {
      poses.push_back({s.t_ns - shift_ns, s.p_w_b, s.q_w_b});
    }
    vio::CurveFitOptions fit;
    fit.knot_spacing_s = args.knot_spacing_s;
    fit.rotation_knot_spacing_s = args.rotation_knot_spacing_s;
    std::vector<vio::ImuSample> imu = flight.imu;
    std::optional<vio::TrajectoryCurve> curve;
    if (args.curve == vio::FlightCurve::kGroundTruthAndImu) {
      const vio::ImuCurveFit joint = vio::FitCurveToImu(
          poses, flight.imu,
          flight.has_imu_noise ? flight.imu_noise : vio::ImuNoise(),
          args.imu_curve);
      PrintJointFit(joint.report, args.imu_curve);
      for (vio::ImuSample& s : imu) {
        s.gyr -= joint.GyroBiasAt(s.t_ns);
        s.acc -= joint.AccelBiasAt(s.t_ns);
      }
      curve.emplace(joint.curve);
    } else {
      curve.emplace(poses, fit);
    }
    vio::ImuCurveResidualOptions options;
    options.max_offset_s = args.max_offset_s;
    const vio::ImuCurveResidual r =
        vio::CompareImuWithCurve(*curve, imu, options);

    std::printf("flight %s: %d IMU samples at %.1f Hz against the curve "
                "(knots %.4f s, rotations %.4f s, ground truth moved by "
                "%.4f s)\n",
                args.flight.c_str(), r.samples, r.sample_rate_hz,
                args.knot_spacing_s,
                args.rotation_knot_spacing_s > 0.0
                    ? args.rotation_knot_spacing_s
                    : args.knot_spacing_s,
                -args.offset_s);
    std::printf("best offset: gyroscope %+.2f ms, accelerometer %+.2f ms\n",
                r.gyr_offset_s * 1e3, r.acc_offset_s * 1e3);
    std::printf("\n| residual rms (bias removed) | x | y | z |\n"
                "| --- | --- | --- | --- |\n");
    PrintAxes("gyroscope at 0 [mrad/s]", r.gyr_rms_at_zero, 1e3);
    PrintAxes("gyroscope at best [mrad/s]", r.gyr_rms_at_best, 1e3);
    PrintAxes("accelerometer at 0 [m/s^2]", r.acc_rms_at_zero, 1.0);
    PrintAxes("accelerometer at gyro's best [m/s^2]", r.acc_rms_at_best, 1.0);
    if (flight.has_imu_noise) {
      const double root_rate = std::sqrt(r.sample_rate_hz);
      std::printf("sensor.yaml white noise per sample: gyroscope %.4g mrad/s, "
                  "accelerometer %.4g m/s^2\n",
                  flight.imu_noise.gyroscope_noise_density * root_rate * 1e3,
                  flight.imu_noise.accelerometer_noise_density * root_rate);
    }
    std::printf(
        "\nAllan deviation at the gyroscope's best offset, as an equivalent "
        "white-noise density adev(tau) sqrt(tau)\n\n"
        "| tau [s] | gyroscope x, y, z [rad/s/sqrt(Hz)] | accelerometer x, y, "
        "z [m/s^2/sqrt(Hz)] |\n| --- | --- | --- |\n");
    for (const vio::AllanPoint& p : r.allan) {
      const double root_tau = std::sqrt(p.tau_s);
      std::printf("| %.3f | %.2e, %.2e, %.2e | %.2e, %.2e, %.2e |\n", p.tau_s,
                  p.gyr.x() * root_tau, p.gyr.y() * root_tau,
                  p.gyr.z() * root_tau, p.acc.x() * root_tau,
                  p.acc.y() * root_tau, p.acc.z() * root_tau);
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
