// The bounded IMU stamp filter (dataset/imu_stamp_filter.h), fed a line at a
// time, against the filter that took the whole file
// (test/testing/whole_file_imu_stamp_filter.h): the same samples and the
// same counts on randomised glitchy inputs (fixed seed); the one-line
// look-ahead; and the case one line of look-ahead cannot repair.

#include "dataset/imu_stamp_filter.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "test/testing/glitchy_imu_lines.h"
#include "test/testing/whole_file_imu_stamp_filter.h"

namespace vio {
namespace {

using testing::InjectStampGlitches;
using testing::WholeFileImuStampFilter;

std::vector<ImuSample> Streamed(const std::vector<ImuLine>& lines,
                                ImuStampReport* report) {
  ImuStampFilter filter(report);
  std::vector<ImuSample> kept;
  ImuSample s;
  for (const ImuLine& l : lines) {
    if (filter.Add(l, &s)) kept.push_back(s);
  }
  if (filter.Finish(&s)) kept.push_back(s);
  return kept;
}

// `n` clean lines at 200 Hz whose values cycle through three, so that
// repeated stamps are sometimes exact repeats.
std::vector<ImuLine> CleanLines(int n) {
  std::vector<ImuLine> lines(n);
  for (int i = 0; i < n; ++i) {
    lines[i].sample.t_ns = 1000000000 + 5000000LL * i;
    lines[i].sample.gyr = Eigen::Vector3d(0.1 * (i % 3), 0.2, 0.3);
    lines[i].sample.acc = Eigen::Vector3d(9.8, 0.0, 0.1 * (i % 3));
    lines[i].line = i + 2;
  }
  return lines;
}

void ExpectSameReport(const ImuStampReport& a, const ImuStampReport& b) {
  EXPECT_EQ(a.repeated_lines, b.repeated_lines);
  EXPECT_EQ(a.conflicting_repeats, b.conflicting_repeats);
  EXPECT_EQ(a.out_of_order, b.out_of_order);
  EXPECT_EQ(a.first_repeated_line, b.first_repeated_line);
  EXPECT_EQ(a.first_conflict_line, b.first_conflict_line);
  EXPECT_EQ(a.first_out_of_order_line, b.first_out_of_order_line);
  EXPECT_EQ(a.first_conflict_t_ns, b.first_conflict_t_ns);
}

// Expects both filters to agree on `lines` (samples bit for bit and every
// count); false once the test has a failure.
bool ExpectSameAsWholeFile(const std::vector<ImuLine>& lines,
                           ImuStampReport* whole_report) {
  ImuStampReport streamed_report;
  const std::vector<ImuSample> whole =
      WholeFileImuStampFilter(lines, whole_report);
  const std::vector<ImuSample> streamed = Streamed(lines, &streamed_report);
  ExpectSameReport(*whole_report, streamed_report);
  EXPECT_EQ(whole.size(), streamed.size());
  for (size_t i = 0; i < whole.size() && i < streamed.size(); ++i) {
    EXPECT_EQ(whole[i].t_ns, streamed[i].t_ns) << "sample " << i;
    EXPECT_EQ(whole[i].acc, streamed[i].acc) << "sample " << i;
    EXPECT_EQ(whole[i].gyr, streamed[i].gyr) << "sample " << i;
  }
  return !::testing::Test::HasFailure();
}

TEST(ImuStampFilter, RandomGlitchyInputsGiveTheWholeFileFiltersSamples) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> length(1, 80);
  std::uniform_real_distribution<double> rate(0.02, 0.5);
  ImuStampReport totals;
  int64_t dropped = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<ImuLine> lines = CleanLines(length(rng));
    InjectStampGlitches(&lines, rate(rng), &rng);
    ImuStampReport report;
    if (!ExpectSameAsWholeFile(lines, &report)) {
      ADD_FAILURE() << "trial " << trial << " (" << lines.size() << " lines)";
      return;
    }
    totals.repeated_lines += report.repeated_lines;
    totals.conflicting_repeats += report.conflicting_repeats;
    totals.out_of_order += report.out_of_order;
    dropped += report.dropped();
  }
  // Not vacuous: every kind of drop happened, many times.
  EXPECT_GT(totals.repeated_lines, 100);
  EXPECT_GT(totals.conflicting_repeats, 100);
  EXPECT_GT(totals.out_of_order, 1000);
}

TEST(ImuStampFilter, GivesEachVerdictWhenTheNextLineArrives) {
  // One line of look-ahead: the sample of line k comes out of Add(line k+1);
  // nothing more is held.
  const std::vector<ImuLine> lines = CleanLines(5);
  ImuStampReport report;
  ImuStampFilter filter(&report);
  ImuSample s;
  EXPECT_FALSE(filter.Add(lines[0], &s));
  for (size_t k = 1; k < lines.size(); ++k) {
    ASSERT_TRUE(filter.Add(lines[k], &s)) << k;
    EXPECT_EQ(s.t_ns, lines[k - 1].sample.t_ns);
  }
  ASSERT_TRUE(filter.Finish(&s));
  EXPECT_EQ(s.t_ns, lines.back().sample.t_ns);
  EXPECT_FALSE(filter.Finish(&s));
  EXPECT_EQ(report.dropped(), 0);
}

std::vector<int64_t> KeptStamps(const std::vector<int64_t>& stamps,
                                ImuStampReport* report) {
  std::vector<ImuLine> lines = CleanLines(static_cast<int>(stamps.size()));
  for (size_t i = 0; i < stamps.size(); ++i) lines[i].sample.t_ns = stamps[i];
  std::vector<int64_t> kept;
  for (const ImuSample& s : Streamed(lines, report)) kept.push_back(s.t_ns);
  ImuStampReport whole;
  EXPECT_EQ(WholeFileImuStampFilter(lines, &whole).size(), kept.size());
  return kept;
}

TEST(ImuStampFilter, ASingleFutureStampIsDropped) {
  ImuStampReport report;
  EXPECT_EQ(KeptStamps({10, 20, 900, 30, 40}, &report),
            (std::vector<int64_t>{10, 20, 30, 40}));
  EXPECT_EQ(report.out_of_order, 1);
  EXPECT_EQ(report.first_out_of_order_line, 4);
}

TEST(ImuStampFilter, ARunOfFutureStampsIsKept) {
  // Two consecutive stamps ahead: each fits before the next, so both are
  // kept and the good samples behind them are dropped until the stamps
  // pass them (as the whole-file filter did: one line of look-ahead there
  // too). The documented limit (dataset/imu_stamp_filter.h).
  ImuStampReport report;
  EXPECT_EQ(KeptStamps({10, 20, 900, 910, 30, 40, 920}, &report),
            (std::vector<int64_t>{10, 20, 900, 910, 920}));
  EXPECT_EQ(report.out_of_order, 2);
  EXPECT_EQ(report.first_out_of_order_line, 6);
}

}  // namespace
}  // namespace vio
