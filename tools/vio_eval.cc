// vio_eval: compares an estimated trajectory with ground truth the way evo's
// evo_ape / evo_rpe do (association, Umeyama alignment, ATE, RPE) and prints
// one figure per line: "<name> <value> <unit>". Optionally draws a PNG.

#include <Eigen/Geometry>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset/trajectory_io.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "eval/plot.h"
#include "tools/command_line.h"

namespace {

struct Args {
  std::string estimate_path;
  std::string ground_truth_path;
  vio::AlignmentMode align = vio::AlignmentMode::kSe3;
  vio::AssociationOptions association;
  std::string plot_path;  // empty: no plot
  vio::RpeUnit rpe_unit = vio::RpeUnit::kMeters;
  std::vector<double> rpe_deltas = {1.0, 2.0, 5.0, 10.0};
  bool help = false;
};

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

constexpr char kUsage[] =
    "usage: vio_eval EST GT [--align se3|sim3|posyaw|none] [--max-diff S]\n"
    "                [--plot FILE.png] [--rpe-unit m|f] [--rpe-deltas "
    "D,D,...]\n"
    "\n"
    "EST and GT are TUM files (t x y z qx qy qz qw, t in seconds), EuRoC\n"
    "CSVs (t[ns], p, q(w,x,y,z), ...) or KITTI pose files (12 numbers, no\n"
    "stamps); the format is told from the content. Each pose of the shorter\n"
    "trajectory (the estimate when both are equally long) is paired with the\n"
    "nearest stamp of the other within --max-diff, as evo does; two KITTI\n"
    "files are paired line by line. The estimate is aligned to the ground\n"
    "truth and ATE and RPE are printed, one figure per line.\n"
    "\n"
    "  --align A        se3 (default; = evo_ape --align), sim3 (= --align\n"
    "                   --correct_scale), posyaw (4-DoF, yaw + translation),\n"
    "                   none\n"
    "  --max-diff S     largest stamp difference to associate [s] (default "
    "0.01)\n"
    "  --plot FILE.png  also draw the top view and the error over time\n"
    "  --rpe-unit U     RPE deltas in metres travelled (m, default) or in\n"
    "                   associated poses (f)\n"
    "  --rpe-deltas L   comma-separated RPE deltas (default 1,2,5,10)\n"
    "  --help           this text\n";

std::vector<double> ParseList(const std::string& flag,
                              const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    values.push_back(vio::ParseNumber<double>(flag, item));
  if (values.empty()) throw std::invalid_argument(flag + " expects a list");
  return values;
}

Args ParseArgs(int argc, char** argv) {
  Args args;
  std::vector<std::string> positional;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string arg = line.Current();
    if (arg == "--help" || arg == "-h") {
      args.help = true;
      return args;
    } else if (arg == "--align") {
      args.align = vio::ParseAlignmentMode(line.Value());
    } else if (arg == "--max-diff") {
      args.association.max_diff = line.Number<double>();
    } else if (arg == "--plot") {
      args.plot_path = line.Value();
    } else if (arg == "--rpe-unit") {
      const std::string unit = line.Value();
      if (unit != "m" && unit != "f") {
        throw std::invalid_argument("--rpe-unit expects m or f (got '" + unit +
                                    "')");
      }
      args.rpe_unit =
          unit == "m" ? vio::RpeUnit::kMeters : vio::RpeUnit::kFrames;
    } else if (arg == "--rpe-deltas") {
      args.rpe_deltas = ParseList(arg, line.Value());
    } else if (!arg.empty() && arg[0] == '-' && arg.size() > 1) {
      throw std::invalid_argument("unknown option " + arg + "\n" + kUsage);
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 2) {
    throw std::invalid_argument("expected EST and GT files\n" +
                                std::string(kUsage));
  }
  args.estimate_path = positional[0];
  args.ground_truth_path = positional[1];
  args.association.Validate();
  // RpePairs validates a delta; on an empty trajectory that is all it does.
  for (double d : args.rpe_deltas) vio::RpePairs({}, d, args.rpe_unit);
  return args;
}

void PrintStats(const std::string& name, const vio::ErrorStats& s,
                const char* unit) {
  const std::pair<const char*, double> rows[] = {
      {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
      {"std", s.std},   {"min", s.min},   {"max", s.max}};
  for (const auto& [stat, v] : rows) {
    std::cout << name << ' ' << stat << ' ' << v << ' ' << unit << '\n';
  }
}

std::string Join(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(6);
  out << v.x() << ' ' << v.y() << ' ' << v.z();
  return out.str();
}

void PrintAlignment(const vio::Alignment& a) {
  const Eigen::AngleAxisd aa(a.R_w_e);
  std::cout << "alignment " << vio::AlignmentModeName(a.mode) << '\n'
            << "alignment rotation (row-major)";
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) std::cout << ' ' << a.R_w_e(r, c);
  }
  std::cout << "\nalignment rotation angle " << aa.angle() * kRadToDeg
            << " deg about " << Join(aa.axis()) << '\n'
            << "alignment translation " << Join(a.t_w_e) << " m\n"
            << "alignment scale " << a.scale << '\n';
  if (a.yaw_from_orientations) {
    std::cout << "alignment yaw from the orientations: the ground truth "
                 "spans less than "
              << vio::kPosYawMinSpread << " m in x-y\n";
  }
}

std::string BaseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

const char* UnitName(vio::RpeUnit unit) {
  return unit == vio::RpeUnit::kMeters ? "m" : "f";
}

void PrintInputs(const Args& args, const vio::TrajectoryFile& estimate,
                 const vio::TrajectoryFile& ground_truth) {
  std::cout << "estimate " << args.estimate_path << " poses "
            << estimate.poses.size() << " ("
            << vio::TrajectoryFormatName(estimate.format) << ")\n"
            << "ground truth " << args.ground_truth_path << " poses "
            << ground_truth.poses.size() << " ("
            << vio::TrajectoryFormatName(ground_truth.format) << ")\n"
            << "options align " << vio::AlignmentModeName(args.align)
            << ", max diff " << args.association.max_diff << " s, rpe deltas";
  for (double d : args.rpe_deltas)
    std::cout << ' ' << d << UnitName(args.rpe_unit);
  std::cout << '\n';
}

// By stamp (evo's rule, eval/association.h) or, for two KITTI files, by line.
vio::Association AssociateFiles(const Args& args,
                                const vio::TrajectoryFile& estimate,
                                const vio::TrajectoryFile& ground_truth) {
  if (estimate.stamped() && ground_truth.stamped()) {
    return vio::Associate(estimate.poses, ground_truth.poses, args.association);
  }
  if (estimate.stamped() || ground_truth.stamped()) {
    throw std::invalid_argument(
        "a KITTI pose file has no stamps: it pairs only with another KITTI "
        "file, line by line (as evo's kitti mode)");
  }
  std::cout << "association by line (KITTI)\n";
  return vio::AssociateByIndex(estimate.poses, ground_truth.poses);
}

void CheckEnoughAssociations(const Args& args, size_t count) {
  if (count < vio::MinimumPoses(args.align)) {
    throw std::runtime_error(
        "too few associations: " + std::to_string(count) +
        " pose pairs within " + std::to_string(args.association.max_diff) +
        " s, the " + vio::AlignmentModeName(args.align) + " alignment needs " +
        std::to_string(vio::MinimumPoses(args.align)) +
        " (do both files cover the same time? try --max-diff)");
  }
}

void PrintRpe(const Args& args, const vio::Trajectory& aligned,
              const vio::Trajectory& ground_truth) {
  for (double delta : args.rpe_deltas) {
    const vio::RelativePoseError rpe =
        vio::ComputeRpe(aligned, ground_truth, delta, args.rpe_unit);
    std::ostringstream name;
    name << "RPE " << delta << UnitName(args.rpe_unit);
    std::cout << name.str() << " pairs " << rpe.pairs.size() << '\n';
    if (rpe.pairs.empty()) continue;
    PrintStats(name.str() + " trans", rpe.translation, "m");
    PrintStats(name.str() + " rot", rpe.rotation, "deg");
  }
}

void Plot(const Args& args, bool stamped, const vio::Trajectory& ground_truth,
          const vio::Trajectory& aligned,
          const vio::AbsoluteTrajectoryError& ate) {
  vio::PlotOptions options;
  std::ostringstream title;
  title << "vio_eval: " << BaseName(args.estimate_path) << " vs "
        << BaseName(args.ground_truth_path) << ", "
        << vio::AlignmentModeName(args.align) << " alignment, ATE rmse "
        << ate.translation.rmse << " m";
  options.title = title.str();
  options.estimate_label = std::string("estimate (") +
                           vio::AlignmentModeName(args.align) + " aligned)";
  if (!stamped) options.time_label = "pose index (KITTI files: no stamps)";
  vio::WriteEvaluationPlot(args.plot_path, ground_truth, aligned,
                           ate.translation_m, options);
  std::cout << "plot " << args.plot_path << '\n';
}

int Run(const Args& args) {
  if (args.help) {
    std::cout << kUsage;
    return 0;
  }
  std::cout.precision(6);
  const vio::TrajectoryFile estimate =
      vio::ReadTrajectoryFile(args.estimate_path);
  const vio::TrajectoryFile ground_truth =
      vio::ReadTrajectoryFile(args.ground_truth_path);
  PrintInputs(args, estimate, ground_truth);

  const vio::Association assoc = AssociateFiles(args, estimate, ground_truth);
  std::cout << "associated poses " << assoc.size() << '\n';
  CheckEnoughAssociations(args, assoc.size());
  const vio::Alignment alignment =
      vio::Align(assoc.estimate, assoc.ground_truth, args.align);
  PrintAlignment(alignment);
  const vio::Trajectory aligned = alignment.Apply(assoc.estimate);

  const vio::AbsoluteTrajectoryError ate =
      vio::ComputeAte(aligned, assoc.ground_truth);
  PrintStats("ATE", ate.translation, "m");
  PrintStats("ATE rot", ate.rotation, "deg");
  PrintRpe(args, aligned, assoc.ground_truth);
  if (!args.plot_path.empty()) {
    Plot(args, estimate.stamped(), assoc.ground_truth, aligned, ate);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(ParseArgs(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
}
