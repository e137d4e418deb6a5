// curve_fitting: the LM exercise of the user's notes. Fits y = exp(a x^2 +
// b x + c) to noisy samples with Ceres' Levenberg-Marquardt and with the
// hand-written LM of levenberg_marquardt.h, optionally with gross outliers
// and a robust kernel, and prints both iteration logs and the estimates side
// by side. See docs/curve_fitting.md.

#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "tools/command_line.h"
#include "tools/curve_fitting/curve_ceres.h"
#include "tools/curve_fitting/curve_plot.h"
#include "tools/curve_fitting/curve_problem.h"
#include "tools/curve_fitting/levenberg_marquardt.h"

namespace {

struct Args {
  vio::CurveProblemOptions problem;
  vio::LmOptions lm;
  std::string plot;  // empty: no plot
  bool help = false;
};

constexpr char kUsage[] =
    "usage: curve_fitting [--a A] [--b B] [--c C] [--n N] [--sigma S]\n"
    "                     [--seed N] [--damping nielsen|marquardt] [--tau T]\n"
    "                     [--outliers FRACTION] [--kernel none|huber|cauchy]\n"
    "                     [--max-iter N] [--plot FILE.png] [--help]\n"
    "\n"
    "Draws N samples of y = exp(a x^2 + b x + c) + n, n ~ N(0, S^2), at\n"
    "x = i/N, and fits (a, b, c) from (0, 0, 0) with Ceres' Levenberg-\n"
    "Marquardt and with the hand-written LM of the user's notes. Prints both\n"
    "iteration logs, then the estimates, the ground truth, the iterations and\n"
    "the time side by side.\n"
    "\n"
    "  --a, --b, --c  true parameters (default 1, 2, 1)\n"
    "  --n N          number of samples, >= 3 (default 100)\n"
    "  --sigma S      noise standard deviation, >= 0 (default 1)\n"
    "  --seed N       random seed of noise and outliers (default 42)\n"
    "  --damping D    hand LM damping update: nielsen or marquardt\n"
    "                 (default nielsen)\n"
    "  --tau T        hand LM initial damping mu0 = T max diag(J^T J)\n"
    "                 (default 1e-3)\n"
    "  --outliers F   fraction of samples made gross outliers, in [0, 1]: y\n"
    "                 += U(10, 30) S (default 0)\n"
    "  --kernel K     robust kernel of both solvers: none, huber\n"
    "                 (c = 1.345 S) or cauchy (c = 2.3849 S) (default none)\n"
    "  --max-iter N   iteration limit of both solvers (default 100)\n"
    "  --plot FILE    write a PNG of the samples, the truth and both fits\n"
    "  --help         this text\n";

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::KernelType kernel = vio::KernelType::kNone;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--help" || a == "-h") {
      args.help = true;
    } else if (a == "--a") {
      args.problem.truth[vio::kCurveA] = line.Number<double>();
    } else if (a == "--b") {
      args.problem.truth[vio::kCurveB] = line.Number<double>();
    } else if (a == "--c") {
      args.problem.truth[vio::kCurveC] = line.Number<double>();
    } else if (a == "--n") {
      args.problem.num_samples = line.Number<int>();
    } else if (a == "--sigma") {
      args.problem.sigma = line.Number<double>();
    } else if (a == "--seed") {
      const long long seed = line.Number<long long>();
      if (seed < 0 || seed > 0xffffffffLL) {
        throw std::invalid_argument("--seed must be in [0, 2^32)");
      }
      args.problem.seed = static_cast<uint32_t>(seed);
    } else if (a == "--damping") {
      const std::string name = line.Value();
      if (!vio::ParseLmDamping(name, &args.lm.damping)) {
        throw std::invalid_argument(
            "--damping expects nielsen or marquardt (got '" + name + "')");
      }
    } else if (a == "--tau") {
      args.lm.tau = line.Number<double>();
    } else if (a == "--outliers") {
      args.problem.outlier_fraction = line.Number<double>();
    } else if (a == "--kernel") {
      const std::string name = line.Value();
      if (!vio::ParseKernelType(name, &kernel)) {
        throw std::invalid_argument(
            "--kernel expects none, huber or cauchy (got '" + name + "')");
      }
    } else if (a == "--max-iter") {
      args.lm.max_iterations = line.Number<int>();
    } else if (a == "--plot") {
      args.plot = line.Value();
    } else {
      throw std::invalid_argument("unknown option '" + a + "' (see --help)");
    }
  }
  args.lm.kernel.type = kernel;
  args.lm.kernel.c = (kernel == vio::KernelType::kHuber ? vio::kHuber95Scale
                                                        : vio::kCauchy95Scale) *
                     args.problem.sigma;
  std::string message;
  if (!args.problem.Validate(&message) || !args.lm.Validate(&message)) {
    throw std::invalid_argument(message);
  }
  return args;
}

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now() - start)
      .count();
}

void PrintConfig(const Args& args) {
  const vio::CurveProblemOptions& p = args.problem;
  std::printf(
      "curve_fitting: y = exp(a x^2 + b x + c) + N(0, sigma^2), start (0, 0, "
      "0)\n  truth a=%g b=%g c=%g, n=%d, sigma=%g, seed=%u, outliers=%g, "
      "kernel=%s",
      p.truth[vio::kCurveA], p.truth[vio::kCurveB], p.truth[vio::kCurveC],
      p.num_samples, p.sigma, p.seed, p.outlier_fraction,
      vio::KernelTypeName(args.lm.kernel.type));
  if (args.lm.kernel.type != vio::KernelType::kNone) {
    std::printf(" (c=%g)", args.lm.kernel.c);
  }
  std::printf(", damping=%s, tau=%g, max-iter=%d\n",
              vio::LmDampingName(args.lm.damping), args.lm.tau,
              args.lm.max_iterations);
}

// The hand LM's log as the notes print it: one line per iteration with the
// chi2 reached and the damping after the update; rejected trials indented.
void PrintLmLog(const vio::LmSummary& lm) {
  std::printf("iter: 0 , chi2= %g , lambda= %g\n", lm.initial_chi2,
              lm.initial_mu);
  for (const vio::LmTrial& t : lm.log) {
    if (t.accepted) {
      std::printf("iter: %d , chi2= %g , lambda= %g  (rho= %.3f)\n",
                  t.iteration, t.chi2, t.mu_next, t.gain_ratio);
    } else {
      std::printf("    rejected: chi2= %g , rho= %.3g , lambda %g -> %g\n",
                  t.chi2, t.gain_ratio, t.mu, t.mu_next);
    }
  }
  std::printf("stopped: %s\n", vio::LmTerminationName(lm.termination));
}

void PrintRow(const char* name, const Eigen::Vector3d& p, double chi2,
              int accepted, int trials, double ms) {
  std::printf("%-9s %10.6f %10.6f %10.6f %12.4f %8d/%-5d %10.3f\n", name,
              p[vio::kCurveA], p[vio::kCurveB], p[vio::kCurveC], chi2, accepted,
              trials, ms);
}

int Run(const Args& args) {
  PrintConfig(args);
  const vio::CurveSamples samples = vio::MakeCurveSamples(args.problem);
  const Eigen::Vector3d p0 = Eigen::Vector3d::Zero();

  std::printf("\n== Ceres: LEVENBERG_MARQUARDT, analytic Jacobian ==\n");
  std::fflush(stdout);
  vio::CeresFitOptions ceres_options;
  ceres_options.kernel = args.lm.kernel;
  ceres_options.max_iterations = args.lm.max_iterations;
  ceres_options.progress_to_stdout = true;
  auto start = std::chrono::steady_clock::now();
  const vio::CeresFitResult ceres =
      vio::FitCurveWithCeres(samples, p0, ceres_options);
  const double ceres_ms = MillisecondsSince(start);
  std::cout << std::flush;
  std::printf("%s\n", ceres.summary.BriefReport().c_str());

  std::printf("\n== hand LM: %s damping ==\n",
              vio::LmDampingName(args.lm.damping));
  start = std::chrono::steady_clock::now();
  const vio::LmSummary lm = vio::SolveLevenbergMarquardt(
      vio::CurveResiduals(samples), Eigen::VectorXd(p0), args.lm);
  const double lm_ms = MillisecondsSince(start);
  PrintLmLog(lm);

  std::printf(
      "\n== results (chi2 = sum rho(r^2); iterations accepted/trials) ==\n");
  std::printf("%-9s %10s %10s %10s %12s %14s %10s\n", "", "a", "b", "c", "chi2",
              "iterations", "time [ms]");
  std::printf(
      "%-9s %10.6f %10.6f %10.6f\n", "truth", args.problem.truth[vio::kCurveA],
      args.problem.truth[vio::kCurveB], args.problem.truth[vio::kCurveC]);
  const int ceres_accepted = ceres.summary.num_successful_steps;
  PrintRow("Ceres", ceres.p, 2.0 * ceres.summary.final_cost, ceres_accepted,
           ceres_accepted + ceres.summary.num_unsuccessful_steps, ceres_ms);
  PrintRow("hand LM", lm.p.head<3>(), lm.final_chi2, lm.iterations,
           static_cast<int>(lm.log.size()), lm_ms);

  if (!args.plot.empty()) {
    vio::CurvePlot plot;
    plot.samples = &samples;
    plot.truth = args.problem.truth;
    plot.ceres_fit = ceres.p;
    plot.lm_fit = lm.p.head<3>();
    plot.title = std::string("y = exp(a x^2 + b x + c), n = ") +
                 std::to_string(args.problem.num_samples) + ", kernel " +
                 vio::KernelTypeName(args.lm.kernel.type);
    vio::WriteCurvePlot(args.plot, plot);
    std::printf("wrote %s\n", args.plot.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::cout << kUsage;
      return 0;
    }
    return Run(args);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
