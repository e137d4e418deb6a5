// vio_faults: copies a sequence folder and corrupts the copy in one way (an
// IMU dropout, repeated or disordered stamps, NaN samples, a saturated
// accelerometer, a bias jump, frames without features, outliers, an
// unconfigured time offset, a camera blackout, a halved frame rate), for a
// fault-injection replay (scripts/fault_table.sh, docs/robustness.md).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "config/euroc_sensor.h"
#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/fault_injection.h"
#include "dataset/features_csv.h"
#include "dataset/frame_faults.h"
#include "tools/command_line.h"

namespace {

namespace fs = std::filesystem;

constexpr char kUsage[] =
    "usage: vio_faults --in SEQ --out DIR --fault KIND [--at S] [--duration "
    "S]\n"
    "                  [--count N] [--value X] [--fraction F] [--seed N]\n"
    "\n"
    "Copies the sequence folder SEQ (EuRoC layout with imu0/data.csv and\n"
    "camN/features.csv, as vio_sim writes) to DIR and corrupts the copy in\n"
    "ONE way. Times are seconds after the first IMU sample. KIND:\n"
    "  imu-dropout       --duration S of IMU samples missing (default 0.5)\n"
    "  imu-duplicate     --count N lines from --at each repeated (default 20)\n"
    "  imu-out-of-order  one sample moved --count N places later (default 3)\n"
    "  imu-nan           gyroscope x NaN in --count N samples (default 1)\n"
    "  accel-saturation  accelerometer x pinned at its full scale X m/s^2\n"
    "                    for --duration S, as a shock past the range reads\n"
    "                    (default X = 176.52, the configs' range; S = 0.2)\n"
    "  accel-clipped     accelerometer clipped to +-X m/s^2 per axis for\n"
    "                    --duration S: a range smaller than the motion\n"
    "                    (default X = 9.4, S = 1)\n"
    "  accel-bias-jump   accelerometer x raised by X m/s^2 from --at on\n"
    "                    (default 0.3)\n"
    "  gyro-bias-jump    gyroscope x raised by X rad/s from --at on\n"
    "                    (default 0.02)\n"
    "  empty-frames      a --fraction F of the frames over --duration S lose\n"
    "                    every feature (default F = 0.3, S = 2)\n"
    "  outliers          a --fraction F of the observations over --duration S\n"
    "                    moved to random pixels (default F = 0.4, S = 2)\n"
    "  time-offset       camera stamps moved by X s, not configured\n"
    "                    (default 0.025)\n"
    "  camera-blackout   no frame for --duration S (default 2)\n"
    "  half-rate         every second frame removed from --at on\n"
    "--at S defaults to 4. --seed N (default 1) picks the frames and\n"
    "observations of empty-frames and outliers. Status 0 on success, 1 on an\n"
    "error (a bad option, an unreadable SEQ, DIR/mav0 already there, a fault\n"
    "that does not fit the sequence).\n";

struct Args {
  std::string in, out, fault;
  double at_s = 4.0;
  double duration_s = std::numeric_limits<double>::quiet_NaN();  // kind's
  double value = std::numeric_limits<double>::quiet_NaN();       // defaults
  double fraction = std::numeric_limits<double>::quiet_NaN();
  int count = 0;  // 0: the kind's default
  uint32_t seed = 1;
  bool help = false;
};

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string flag = line.Current();
    if (flag == "--in") {
      args.in = line.Value();
    } else if (flag == "--out") {
      args.out = line.Value();
    } else if (flag == "--fault") {
      args.fault = line.Value();
    } else if (flag == "--at") {
      args.at_s = line.Number<double>();
    } else if (flag == "--duration") {
      args.duration_s = line.Number<double>();
    } else if (flag == "--count") {
      args.count = line.Number<int>();
      if (args.count < 1) throw std::invalid_argument("--count must be >= 1");
    } else if (flag == "--value") {
      args.value = line.Number<double>();
    } else if (flag == "--fraction") {
      args.fraction = line.Number<double>();
    } else if (flag == "--seed") {
      args.seed = line.Number<uint32_t>();
    } else if (flag == "--help" || flag == "-h") {
      args.help = true;
    } else {
      throw std::invalid_argument("unknown argument '" + flag + "'\n" + kUsage);
    }
  }
  if (args.help) return args;
  if (args.in.empty() || args.out.empty() || args.fault.empty()) {
    throw std::invalid_argument(std::string("--in, --out and --fault are "
                                            "required\n") +
                                kUsage);
  }
  if (!std::isfinite(args.at_s) || args.at_s < 0) {
    throw std::invalid_argument("--at must be >= 0 s");
  }
  return args;
}

double Or(double value, double fallback) {
  return std::isnan(value) ? fallback : value;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw vio::DatasetError(path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw vio::DatasetError(path + ": write failed");
}

// The IMU fault for an imu-* or accel/gyro kind; false for a camera kind.
bool ImuFaultFor(const Args& a, double period_s, vio::ImuFault* f) {
  using vio::ImuFaultKind;
  f->t_s = a.at_s;
  const auto samples = [&](double seconds) {
    if (!(seconds > 0)) throw std::invalid_argument("--duration must be > 0");
    return std::max(1, static_cast<int>(std::lround(seconds / period_s)));
  };
  if (a.fault == "imu-dropout") {
    f->kind = ImuFaultKind::kDrop;
    f->count = samples(Or(a.duration_s, 0.5));
  } else if (a.fault == "imu-duplicate") {
    f->kind = ImuFaultKind::kRepeat;
    f->count = a.count > 0 ? a.count : 20;
  } else if (a.fault == "imu-out-of-order") {
    f->kind = ImuFaultKind::kBackwards;
    f->count = a.count > 0 ? a.count : 3;
  } else if (a.fault == "imu-nan") {
    f->kind = ImuFaultKind::kGyroValue;
    f->count = a.count > 0 ? a.count : 1;
    f->value = std::numeric_limits<double>::quiet_NaN();
  } else if (a.fault == "accel-saturation") {
    f->kind = ImuFaultKind::kAccelValue;
    f->count = samples(Or(a.duration_s, 0.2));
    f->value = Or(a.value, 176.52);
  } else if (a.fault == "accel-clipped") {
    f->kind = ImuFaultKind::kSaturate;
    f->count = samples(Or(a.duration_s, 1.0));
    f->value = Or(a.value, 9.4);
  } else if (a.fault == "accel-bias-jump") {
    f->kind = ImuFaultKind::kAccelStep;
    f->value = Or(a.value, 0.3);
  } else if (a.fault == "gyro-bias-jump") {
    f->kind = ImuFaultKind::kGyroStep;
    f->value = Or(a.value, 0.02);
  } else {
    return false;
  }
  return true;
}

vio::FrameFault FrameFaultFor(const Args& a, const std::string& cam0_yaml) {
  using vio::FrameFaultKind;
  vio::FrameFault f;
  f.t_s = a.at_s;
  f.seed = a.seed;
  if (a.fault == "empty-frames") {
    f.kind = FrameFaultKind::kEmptyFrames;
    f.duration_s = Or(a.duration_s, 2.0);
    f.fraction = Or(a.fraction, 0.3);
  } else if (a.fault == "outliers") {
    f.kind = FrameFaultKind::kOutliers;
    f.duration_s = Or(a.duration_s, 2.0);
    f.fraction = Or(a.fraction, 0.4);
    const vio::CameraCalibration c = vio::ReadEurocCameraYaml(cam0_yaml);
    f.width = c.width;
    f.height = c.height;
  } else if (a.fault == "time-offset") {
    f.kind = FrameFaultKind::kTimeOffset;
    f.offset_s = Or(a.value, 0.025);
  } else if (a.fault == "camera-blackout") {
    f.kind = FrameFaultKind::kBlackout;
    f.duration_s = Or(a.duration_s, 2.0);
  } else if (a.fault == "half-rate") {
    f.kind = FrameFaultKind::kHalfRate;
    f.duration_s = Or(a.duration_s, 0.0);
  } else {
    throw std::invalid_argument("unknown fault '" + a.fault + "'\n" + kUsage);
  }
  std::string message;
  if (!f.Validate(&message)) throw std::invalid_argument(message);
  return f;
}

// The median step between IMU stamps [s].
double ImuPeriod(const vio::EurocData& data) {
  std::vector<int64_t> steps;
  for (size_t i = 1; i < data.imu.size(); ++i) {
    steps.push_back(data.imu[i].t_ns - data.imu[i - 1].t_ns);
  }
  if (steps.empty()) throw std::invalid_argument("the IMU has one sample");
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2,
                   steps.end());
  return 1e-9 * static_cast<double>(steps[steps.size() / 2]);
}

void Run(const Args& args) {
  const vio::EurocData data = vio::ReadEurocFolder(args.in);
  const std::string out_mav0 = vio::JoinPath(args.out, "mav0");
  if (fs::exists(out_mav0)) {
    throw std::invalid_argument(out_mav0 + ": already exists");
  }
  // Checked before the copy, so a bad fault leaves no half-made folder.
  vio::ImuFault imu_fault;
  const bool imu = ImuFaultFor(args, ImuPeriod(data), &imu_fault);
  const std::string in_mav0 = vio::JoinPath(args.in, "mav0");
  if (imu) {
    const std::string csv = ReadText(vio::JoinPath(in_mav0, "imu0/data.csv"));
    const std::string faulted = vio::WithImuFaultInCsv(csv, imu_fault);
    fs::create_directories(args.out);
    fs::copy(in_mav0, out_mav0, fs::copy_options::recursive);
    WriteText(vio::JoinPath(out_mav0, "imu0/data.csv"), faulted);
    std::printf("%s\nwrote %s\n", imu_fault.Describe().c_str(),
                args.out.c_str());
    return;
  }
  const vio::FrameFault fault =
      FrameFaultFor(args, vio::JoinPath(in_mav0, "cam0/sensor.yaml"));
  for (const vio::EurocCamera& c : data.cameras) {
    if (!c.has_features) {
      throw std::invalid_argument(c.folder +
                                  ": no features.csv (camera faults need one)");
    }
  }
  const std::vector<vio::FeatureFrame> frames = vio::WithFrameFault(
      vio::MergedFeatureFrames(data), fault, data.imu.front().t_ns);
  fs::create_directories(args.out);
  fs::copy(in_mav0, out_mav0, fs::copy_options::recursive);
  for (const vio::EurocCamera& c : data.cameras) {
    vio::WriteFeaturesCsv(
        vio::JoinPath(out_mav0,
                      "cam" + std::to_string(c.index) + "/features.csv"),
        frames, c.index);
  }
  std::printf("%s\nwrote %s\n", fault.Describe().c_str(), args.out.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::cout << kUsage;
      return 0;
    }
    Run(args);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
