#include "dataset/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

#include "dataset/csv.h"
#include "dataset/decimal_stamp.h"

namespace vio {
namespace {

// evo's quaternion and rotation matrices are read as they are; ours must be
// within 1e-3 of unit norm (orthonormal), as 6-digit files are, and are then
// normalised.
constexpr double kRotationTolerance = 1e-3;

Eigen::Quaterniond CheckedQuaternion(const CsvReader& csv, double w, double x,
                                     double y, double z) {
  Eigen::Quaterniond q(w, x, y, z);
  if (std::abs(q.norm() - 1.0) > kRotationTolerance) {
    csv.Fail("quaternion is not of unit norm (norm " +
             std::to_string(q.norm()) + ")");
  }
  q.normalize();
  return q;
}

// `strict`: each stamp after the previous one; otherwise a stamp may repeat
// the previous one (see the header) but never go back.
void CheckStampOrder(const CsvReader& csv, const Trajectory& so_far,
                     int64_t t_ns, bool strict) {
  if (so_far.empty()) return;
  const int64_t previous = so_far.back().t_ns;
  if (t_ns < previous || (strict && t_ns == previous)) {
    csv.Fail("timestamp " + std::to_string(t_ns) +
             (strict ? " is not after" : " is before") + " the previous one (" +
             std::to_string(previous) + ")");
  }
}

int64_t SecondsToNs(const CsvReader& csv, const std::string& text) {
  int64_t t_ns = 0;
  switch (ParseDecimalSeconds(text, &t_ns)) {
    case DecimalStampStatus::kOk:
      return t_ns;
    case DecimalStampStatus::kOutOfRange:
      csv.Fail("timestamp is out of range ('" + text + "', at most 9e9 s)");
    case DecimalStampStatus::kNotANumber:
      break;
  }
  csv.Fail("timestamp is not a number of seconds ('" + text + "')");
}

bool IsInteger(const std::string& text) {
  const size_t start = (!text.empty() && (text[0] == '-' || text[0] == '+'));
  if (text.size() == start) return false;
  for (size_t i = start; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
  }
  return true;
}

void ExpectFieldCount(const CsvReader& csv, size_t n, const char* format) {
  csv.ExpectAtLeast(n);
  if (csv.size() != n) {
    csv.Fail(std::string("a ") + format + " line has " + std::to_string(n) +
             " fields, got " + std::to_string(csv.size()));
  }
}

// The rotation block of a KITTI line: orthonormal within the tolerance with
// determinant +1, returned as the nearest unit quaternion.
Eigen::Quaterniond CheckedRotation(const CsvReader& csv,
                                   const Eigen::Matrix3d& R) {
  const double off =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > kRotationTolerance || R.determinant() <= 0.0) {
    csv.Fail("the 3x3 block is not a rotation (|R^T R - I| = " +
             std::to_string(off) +
             ", det = " + std::to_string(R.determinant()) + ")");
  }
  return Eigen::Quaterniond(R).normalized();
}

std::ofstream OpenForWriting(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw DatasetError(path + ": cannot open the file for writing");
  out << std::setprecision(9);
  return out;
}

std::string NsToSeconds(int64_t t_ns) {
  char buf[32];
  const int64_t s = t_ns / 1000000000LL;
  const int64_t ns = std::llabs(t_ns % 1000000000LL);
  std::snprintf(buf, sizeof(buf), "%s%lld.%09lld",
                (t_ns < 0 && s == 0) ? "-" : "", static_cast<long long>(s),
                static_cast<long long>(ns));
  return buf;
}

}  // namespace

const char* TrajectoryFormatName(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kTum:
      return "TUM";
    case TrajectoryFormat::kEuroc:
      return "EuRoC CSV";
    case TrajectoryFormat::kKitti:
      return "KITTI";
  }
  return "?";
}

std::vector<StampedState> ReadEurocGroundTruth(const std::string& path) {
  std::vector<StampedState> out;
  ForEachEurocGroundTruth(path,
                          [&](const StampedState& s) { out.push_back(s); });
  return out;
}

int64_t ForEachEurocGroundTruth(
    const std::string& path,
    const std::function<void(const StampedState&)>& take) {
  CsvReader csv(path);
  int64_t count = 0;
  Trajectory previous;  // the last state's pose only, for the order check
  while (csv.Next()) {
    csv.ExpectAtLeast(17);
    StampedState s;
    s.t_ns = csv.Int64(0);
    CheckStampOrder(csv, previous, s.t_ns, /*strict=*/true);
    s.p_w_b = {csv.Double(1), csv.Double(2), csv.Double(3)};
    s.q_w_b = CheckedQuaternion(csv, csv.Double(4), csv.Double(5),
                                csv.Double(6), csv.Double(7));
    s.v_w = {csv.Double(8), csv.Double(9), csv.Double(10)};
    s.b_g = {csv.Double(11), csv.Double(12), csv.Double(13)};
    s.b_a = {csv.Double(14), csv.Double(15), csv.Double(16)};
    take(s);
    ++count;
    previous.assign(1, PoseOf(s));
  }
  if (count == 0) throw DatasetError(path + ": holds no ground-truth line");
  return count;
}

Trajectory ReadTum(const std::string& path) {
  CsvReader csv(path);
  Trajectory out;
  while (csv.Next()) {
    ExpectFieldCount(csv, 8, "TUM");
    StampedPose p;
    p.t_ns = SecondsToNs(csv, csv.String(0));
    CheckStampOrder(csv, out, p.t_ns, /*strict=*/false);
    p.p_w_b = {csv.Double(1), csv.Double(2), csv.Double(3)};
    p.q_w_b = CheckedQuaternion(csv, csv.Double(7), csv.Double(4),
                                csv.Double(5), csv.Double(6));
    out.push_back(p);
  }
  if (out.empty()) throw DatasetError(path + ": holds no pose line");
  return out;
}

// Every line has as many fields as the first (a matrix, as evo reads it),
// each a finite number; only the pose is kept.
Trajectory ReadEurocPoses(const std::string& path) {
  CsvReader csv(path);
  Trajectory out;
  size_t fields = 0;
  while (csv.Next()) {
    if (out.empty()) {
      csv.ExpectAtLeast(8);
      fields = csv.size();
    }
    ExpectFieldCount(csv, fields, "EuRoC CSV");
    StampedPose p;
    p.t_ns = csv.Int64(0);
    CheckStampOrder(csv, out, p.t_ns, /*strict=*/false);
    p.p_w_b = {csv.Double(1), csv.Double(2), csv.Double(3)};
    p.q_w_b = CheckedQuaternion(csv, csv.Double(4), csv.Double(5),
                                csv.Double(6), csv.Double(7));
    for (size_t i = 8; i < fields; ++i) csv.Double(i);
    out.push_back(p);
  }
  if (out.empty()) throw DatasetError(path + ": holds no pose line");
  return out;
}

Trajectory ReadKitti(const std::string& path) {
  CsvReader csv(path);
  Trajectory out;
  while (csv.Next()) {
    ExpectFieldCount(csv, 12, "KITTI");
    Eigen::Matrix<double, 3, 4> T;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) T(r, c) = csv.Double(4 * r + c);
    }
    StampedPose p;
    p.t_ns = static_cast<int64_t>(out.size()) * 1000000000LL;
    p.p_w_b = T.col(3);
    p.q_w_b = CheckedRotation(csv, T.leftCols<3>());
    out.push_back(p);
  }
  if (out.empty()) throw DatasetError(path + ": holds no pose line");
  return out;
}

TrajectoryFile ReadTrajectoryFile(const std::string& path) {
  CsvReader probe(path);
  if (!probe.Next()) throw DatasetError(path + ": holds no data line");
  TrajectoryFile file;
  if (probe.comma_separated() && probe.size() >= 8 &&
      IsInteger(probe.String(0))) {
    file.format = TrajectoryFormat::kEuroc;
    file.poses = ReadEurocPoses(path);
  } else if (probe.size() == 8) {
    file.format = TrajectoryFormat::kTum;
    file.poses = ReadTum(path);
  } else if (!probe.comma_separated() && probe.size() == 12) {
    file.format = TrajectoryFormat::kKitti;
    file.poses = ReadKitti(path);
  } else {
    probe.Fail("cannot tell the format: " + std::to_string(probe.size()) +
               (probe.comma_separated() ? " comma-separated" : "") +
               " fields (TUM has 8, KITTI 12 separated by blanks, a EuRoC "
               "CSV 8 or more separated by commas, the first an integer)");
  }
  return file;
}

Trajectory ReadTrajectory(const std::string& path) {
  TrajectoryFile file = ReadTrajectoryFile(path);
  if (!file.stamped()) {
    throw DatasetError(path +
                       ": a KITTI pose file has no stamps (pair it with "
                       "another KITTI file by line)");
  }
  return std::move(file.poses);
}

void WriteTum(const std::string& path, const Trajectory& trajectory) {
  std::ofstream out = OpenForWriting(path);
  out << "# t[s] x y z qx qy qz qw (pose of the body frame in the world)\n";
  for (const StampedPose& p : trajectory) {
    const Eigen::Quaterniond& q = p.q_w_b;
    out << NsToSeconds(p.t_ns) << ' ' << p.p_w_b.x() << ' ' << p.p_w_b.y()
        << ' ' << p.p_w_b.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
        << ' ' << q.w() << '\n';
  }
  if (!out) throw DatasetError(path + ": write failed");
}

void WriteStateCsv(const std::string& path,
                   const std::vector<StampedState>& states) {
  std::ofstream out = OpenForWriting(path);
  out << "#timestamp [ns],p_x [m],p_y [m],p_z [m],q_w,q_x,q_y,q_z,"
         "v_x [m/s],v_y [m/s],v_z [m/s],bg_x [rad/s],bg_y [rad/s],"
         "bg_z [rad/s],ba_x [m/s^2],ba_y [m/s^2],ba_z [m/s^2]\n";
  for (const StampedState& s : states) {
    out << s.t_ns;
    const double values[] = {s.p_w_b.x(), s.p_w_b.y(), s.p_w_b.z(), s.q_w_b.w(),
                             s.q_w_b.x(), s.q_w_b.y(), s.q_w_b.z(), s.v_w.x(),
                             s.v_w.y(),   s.v_w.z(),   s.b_g.x(),   s.b_g.y(),
                             s.b_g.z(),   s.b_a.x(),   s.b_a.y(),   s.b_a.z()};
    for (double v : values) out << ',' << v;
    out << '\n';
  }
  if (!out) throw DatasetError(path + ": write failed");
}

void WriteKitti(const std::string& path, const Trajectory& trajectory) {
  std::ofstream out = OpenForWriting(path);
  for (const StampedPose& p : trajectory) {
    const Eigen::Matrix3d R = p.q_w_b.toRotationMatrix();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        out << (c == 3 ? p.p_w_b(r) : R(r, c))
            << (r == 2 && c == 3 ? '\n' : ' ');
      }
    }
  }
  if (!out) throw DatasetError(path + ": write failed");
}

}  // namespace vio
