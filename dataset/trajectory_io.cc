#include "dataset/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "dataset/csv.h"

namespace vio {
namespace {

Eigen::Quaterniond CheckedQuaternion(const CsvReader& csv, double w, double x,
                                     double y, double z) {
  Eigen::Quaterniond q(w, x, y, z);
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    csv.Fail("quaternion is not of unit norm (norm " +
             std::to_string(q.norm()) + ")");
  }
  q.normalize();
  return q;
}

void CheckIncreasing(const CsvReader& csv, int64_t previous, int64_t t_ns,
                     bool first) {
  if (!first && t_ns <= previous) {
    csv.Fail("timestamp " + std::to_string(t_ns) +
             " is not after the previous one (" + std::to_string(previous) +
             ")");
  }
}

bool AllDigits(const std::string& s) {
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Seconds with up to 9 decimals -> integer ns without going through a double
// (1.4e9 s does not fit a double's mantissa at ns resolution). Accepts
// [+-]digits[.digits] with at least one digit; decimals past the 9th are cut.
int64_t SecondsToNs(const CsvReader& csv, const std::string& text) {
  const bool negative = !text.empty() && text[0] == '-';
  const bool signed_text = !text.empty() && (text[0] == '-' || text[0] == '+');
  const std::string body = signed_text ? text.substr(1) : text;
  const size_t dot = body.find('.');
  const std::string whole = body.substr(0, dot);
  std::string frac = dot == std::string::npos ? "" : body.substr(dot + 1);
  if (!AllDigits(whole) || !AllDigits(frac) ||
      (whole.empty() && frac.empty())) {
    csv.Fail("timestamp is not a number of seconds ('" + text + "')");
  }
  // int64 ns hold up to 9.2e9 s.
  if (whole.size() > 10 || std::stoll("0" + whole) >= 9000000000LL) {
    csv.Fail("timestamp is out of range ('" + text + "', at most 9e9 s)");
  }
  if (frac.size() > 9) frac = frac.substr(0, 9);
  while (frac.size() < 9) frac.push_back('0');
  const long long w = std::stoll("0" + whole);
  const long long ns = w * 1000000000LL + std::stoll(frac);
  return negative ? -ns : ns;
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

std::vector<StampedState> ReadEurocGroundTruth(const std::string& path) {
  CsvReader csv(path);
  std::vector<StampedState> out;
  while (csv.Next()) {
    csv.ExpectAtLeast(17);
    StampedState s;
    s.t_ns = csv.Int64(0);
    CheckIncreasing(csv, out.empty() ? 0 : out.back().t_ns, s.t_ns,
                    out.empty());
    s.p_w_b = {csv.Double(1), csv.Double(2), csv.Double(3)};
    s.q_w_b = CheckedQuaternion(csv, csv.Double(4), csv.Double(5),
                                csv.Double(6), csv.Double(7));
    s.v_w = {csv.Double(8), csv.Double(9), csv.Double(10)};
    s.b_g = {csv.Double(11), csv.Double(12), csv.Double(13)};
    s.b_a = {csv.Double(14), csv.Double(15), csv.Double(16)};
    out.push_back(s);
  }
  if (out.empty()) throw DatasetError(path + ": holds no ground-truth line");
  return out;
}

Trajectory ReadTum(const std::string& path) {
  CsvReader csv(path);
  Trajectory out;
  while (csv.Next()) {
    csv.ExpectAtLeast(8);
    if (csv.size() != 8) {
      csv.Fail("a TUM line has 8 fields, got " + std::to_string(csv.size()));
    }
    StampedPose p;
    p.t_ns = SecondsToNs(csv, csv.String(0));
    CheckIncreasing(csv, out.empty() ? 0 : out.back().t_ns, p.t_ns,
                    out.empty());
    p.p_w_b = {csv.Double(1), csv.Double(2), csv.Double(3)};
    p.q_w_b = CheckedQuaternion(csv, csv.Double(7), csv.Double(4),
                                csv.Double(5), csv.Double(6));
    out.push_back(p);
  }
  if (out.empty()) throw DatasetError(path + ": holds no pose line");
  return out;
}

Trajectory ReadTrajectory(const std::string& path) {
  CsvReader probe(path);
  if (!probe.Next()) throw DatasetError(path + ": holds no data line");
  if (probe.size() >= 17) {
    Trajectory out;
    for (const StampedState& s : ReadEurocGroundTruth(path)) {
      out.push_back(PoseOf(s));
    }
    return out;
  }
  if (probe.size() == 8) return ReadTum(path);
  probe.Fail("cannot tell the format: " + std::to_string(probe.size()) +
             " fields (TUM has 8, EuRoC ground truth 17)");
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

}  // namespace vio
