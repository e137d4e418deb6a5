#include "dataset/fault_injection.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace vio {
namespace {

// 20 samples at 200 Hz from t = 1 s, each value telling its index.
std::vector<ImuSample> Stream() {
  std::vector<ImuSample> imu;
  for (int k = 0; k < 20; ++k) {
    ImuSample s;
    s.t_ns = 1000000000 + 5000000LL * k;
    s.gyr = Eigen::Vector3d(k, 0.5, -0.25);
    s.acc = Eigen::Vector3d(9.81, k, 0.125);
    imu.push_back(s);
  }
  return imu;
}

ImuFault Fault(ImuFaultKind kind, double t_s, int count, double value = 0) {
  ImuFault f;
  f.kind = kind;
  f.t_s = t_s;
  f.count = count;
  f.value = value;
  return f;
}

TEST(WithImuFault, EachKindDoesWhatItSays) {
  const std::vector<ImuSample> clean = Stream();
  // At 0.012 s: the first sample at or after it is index 3.
  std::vector<ImuSample> f =
      WithImuFault(clean, Fault(ImuFaultKind::kDrop, 0.012, 5));
  ASSERT_EQ(f.size(), 15u);
  EXPECT_EQ(f[2].gyr.x(), 2);
  EXPECT_EQ(f[3].gyr.x(), 8);
  f = WithImuFault(clean, Fault(ImuFaultKind::kGyroValue, 0.012, 2, 1e308));
  EXPECT_EQ(f[3].gyr.x(), 1e308);
  EXPECT_EQ(f[4].gyr.x(), 1e308);
  EXPECT_EQ(f[5].gyr.x(), 5);
  f = WithImuFault(clean, Fault(ImuFaultKind::kAccelValue, 0.012, 1, 1e6));
  EXPECT_EQ(f[3].acc.x(), 1e6);
  EXPECT_EQ(f[3].gyr.x(), 3);
  f = WithImuFault(clean, Fault(ImuFaultKind::kRepeat, 0.012, 1));
  ASSERT_EQ(f.size(), 21u);
  EXPECT_EQ(f[4].t_ns, f[3].t_ns);
  EXPECT_EQ(f[4].gyr, f[3].gyr);
  f = WithImuFault(clean, Fault(ImuFaultKind::kBackwards, 0.012, 2));
  EXPECT_EQ(f[3].gyr.x(), 4);
  EXPECT_EQ(f[4].gyr.x(), 5);
  EXPECT_EQ(f[5].gyr.x(), 3);  // now after a later stamp
}

TEST(WithImuFault, AFaultThatDoesNotFitIsRefused) {
  EXPECT_THROW(WithImuFault(Stream(), Fault(ImuFaultKind::kDrop, 1.0, 1)),
               std::invalid_argument);
  EXPECT_THROW(WithImuFault(Stream(), Fault(ImuFaultKind::kDrop, 0.095, 2)),
               std::invalid_argument);
  EXPECT_THROW(WithImuFault(Stream(), Fault(ImuFaultKind::kDrop, 0.0, 0)),
               std::invalid_argument);
  EXPECT_THROW(WithImuFault({}, Fault(ImuFaultKind::kDrop, 0.0, 1)),
               std::invalid_argument);
}

// The CSV form keeps every untouched line's text, as sed would: dropping the
// 5 samples from line 5 is `sed '5,9d'`.
TEST(WithImuFaultInCsv, EditsLinesAsSedWould) {
  std::ostringstream text;
  text << "#timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z\n";
  for (int k = 0; k < 20; ++k) {
    text << 1000000000 + 5000000LL * k << "," << k << ",0.5,-0.25,9.81," << k
         << ",0.125\n";
  }
  const std::string csv = text.str();
  std::vector<std::string> lines;
  std::istringstream in(csv);
  for (std::string l; std::getline(in, l);) lines.push_back(l);

  std::string expected;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i + 1 < 5 || i + 1 > 9) expected += lines[i] + "\n";
  }
  EXPECT_EQ(WithImuFaultInCsv(csv, Fault(ImuFaultKind::kDrop, 0.015, 5)),
            expected);
  expected.clear();
  for (size_t i = 0; i < lines.size(); ++i) {
    expected += lines[i] + "\n";
    if (i + 1 == 5) expected += lines[i] + "\n";
  }
  EXPECT_EQ(WithImuFaultInCsv(csv, Fault(ImuFaultKind::kRepeat, 0.015, 1)),
            expected);
  // A changed line is rewritten from its values, the others untouched.
  const std::string glitched =
      WithImuFaultInCsv(csv, Fault(ImuFaultKind::kGyroValue, 0.015, 1, 1e308));
  std::istringstream out(glitched);
  std::vector<std::string> got;
  for (std::string l; std::getline(out, l);) got.push_back(l);
  ASSERT_EQ(got.size(), lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i + 1 != 5) {
      EXPECT_EQ(got[i], lines[i]) << i;
    }
  }
  long long t = 0;
  double v[6];
  ASSERT_EQ(std::sscanf(got[4].c_str(), "%lld,%lf,%lf,%lf,%lf,%lf,%lf", &t,
                        &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]),
            7);
  EXPECT_EQ(t, 1015000000);
  EXPECT_EQ(v[0], 1e308);
  EXPECT_EQ(v[1], 0.5);
  EXPECT_EQ(v[3], 9.81);
  EXPECT_EQ(v[4], 3.0);
  EXPECT_THROW(
      WithImuFaultInCsv("#h\n12,abc\n", Fault(ImuFaultKind::kDrop, 0.0, 1)),
      std::invalid_argument);
}

TEST(SetObservationPixels, CorruptsTheFirstObservationsOfOneFrame) {
  std::vector<FeatureFrame> frames(3);
  for (int k = 0; k < 3; ++k) {
    frames[k].t_ns = 50000000LL * k;
    frames[k].observations.resize(4);
  }
  SetObservationPixels(&frames, 0.04, 2, Eigen::Vector2d(-300, 10));
  EXPECT_EQ(frames[1].observations[0].uv, Eigen::Vector2d(-300, 10));
  EXPECT_EQ(frames[1].observations[1].uv, Eigen::Vector2d(-300, 10));
  EXPECT_EQ(frames[1].observations[2].uv, Eigen::Vector2d::Zero());
  EXPECT_EQ(frames[0].observations[0].uv, Eigen::Vector2d::Zero());
  EXPECT_THROW(SetObservationPixels(&frames, 1.0, 1, Eigen::Vector2d::Zero()),
               std::invalid_argument);
}

}  // namespace
}  // namespace vio
