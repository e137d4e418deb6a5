#include "eval/association.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace vio {
namespace {

constexpr int64_t kMs = 1000000;  // [ns]

// Poses at the given stamps [ns]; x holds the index so pairs can be told.
Trajectory AtStamps(const std::vector<int64_t>& stamps_ns) {
  Trajectory t;
  for (size_t i = 0; i < stamps_ns.size(); ++i) {
    StampedPose p;
    p.t_ns = stamps_ns[i];
    p.p_w_b.x() = static_cast<double>(i);
    t.push_back(p);
  }
  return t;
}

TEST(Association, KeepsOffsetsWithinMaxDiffAndDropsLargerOnes) {
  // Ground truth every 5 ms; estimates 4 ms after a ground-truth stamp (kept
  // with max_diff 10 ms, 1 ms away from the next one) and then one 15 ms
  // beyond the last ground-truth stamp (dropped).
  const Trajectory gt = AtStamps({0, 5 * kMs, 10 * kMs, 15 * kMs, 20 * kMs});
  const Trajectory est = AtStamps({4 * kMs, 14 * kMs, 35 * kMs});
  const Association a = Associate(est, gt, {0.010});
  ASSERT_EQ(a.size(), 2u);
  EXPECT_TRUE(a.walked_estimate);
  EXPECT_EQ(a.estimate[0].t_ns, 4 * kMs);
  EXPECT_EQ(a.ground_truth[0].t_ns, 5 * kMs);  // nearest: 1 ms, not 4 ms
  EXPECT_EQ(a.estimate[1].t_ns, 14 * kMs);
  EXPECT_EQ(a.ground_truth[1].t_ns, 15 * kMs);
  EXPECT_EQ(a.num_estimate_in, 3u);
  EXPECT_EQ(a.num_ground_truth_in, 5u);
}

TEST(Association, MaxDiffIsInclusiveToTheNanosecond) {
  const Trajectory gt = AtStamps({0, 100 * kMs, 200 * kMs});
  const Trajectory est = AtStamps({10 * kMs, 110 * kMs + 1});
  const Association a = Associate(est, gt, {0.010});
  ASSERT_EQ(a.size(), 1u);  // exactly 10 ms kept, 10 ms + 1 ns dropped
  EXPECT_EQ(a.estimate[0].t_ns, 10 * kMs);
  EXPECT_EQ(Associate(est, gt, {0.0101}).size(), 2u);
}

TEST(Association, TieGoesToTheEarlierStamp) {
  const Trajectory gt = AtStamps({0, 10 * kMs, 20 * kMs});
  const Trajectory est = AtStamps({5 * kMs, 15 * kMs});
  const Association a = Associate(est, gt, {0.010});
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a.ground_truth[0].t_ns, 0);
  EXPECT_EQ(a.ground_truth[1].t_ns, 10 * kMs);
}

TEST(Association, AGroundTruthPoseMayServeSeveralEstimates) {
  // evo keeps no uniqueness: both estimates take the same ground truth.
  const Trajectory gt = AtStamps({0, 100 * kMs, 200 * kMs});
  const Trajectory est = AtStamps({99 * kMs, 101 * kMs});
  const Association a = Associate(est, gt, {0.010});
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a.ground_truth[0].t_ns, 100 * kMs);
  EXPECT_EQ(a.ground_truth[1].t_ns, 100 * kMs);
}

TEST(Association, TheShorterTrajectoryIsWalked) {
  // An estimate denser than the ground truth: each ground-truth pose takes
  // its nearest estimate, the other estimates are left out.
  const Trajectory gt = AtStamps({10 * kMs, 50 * kMs});
  const Trajectory est =
      AtStamps({0, 8 * kMs, 12 * kMs, 30 * kMs, 49 * kMs, 52 * kMs});
  const Association a = Associate(est, gt, {0.010});
  EXPECT_FALSE(a.walked_estimate);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a.estimate[0].t_ns, 8 * kMs);  // tie 8/12: the earlier
  EXPECT_EQ(a.estimate[1].t_ns, 49 * kMs);
  EXPECT_EQ(a.ground_truth[1].t_ns, 50 * kMs);
  // Equally long: the estimate is walked, as in evo_ape (the reference is
  // its first argument and is walked only when strictly shorter).
  EXPECT_TRUE(Associate(gt, gt).walked_estimate);
}

TEST(Association, NoOverlapGivesAnEmptyResult) {
  const Trajectory gt = AtStamps({0, 5 * kMs});
  const Trajectory est = AtStamps({1000 * kMs});
  EXPECT_EQ(Associate(est, gt).size(), 0u);
  EXPECT_EQ(Associate({}, gt).size(), 0u);
}

TEST(Association, RejectsUnsortedStampsAndBadMaxDiff) {
  const Trajectory sorted = AtStamps({0, 5 * kMs});
  const Trajectory unsorted = AtStamps({5 * kMs, 5 * kMs});
  EXPECT_THROW(Associate(unsorted, sorted), std::invalid_argument);
  EXPECT_THROW(Associate(sorted, unsorted), std::invalid_argument);
  EXPECT_THROW(Associate(sorted, sorted, {-0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace vio
