#include "eval/association.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <stdexcept>
#include <utility>
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

// evo's matching_time_indices written out as it reads: for each pose of the
// shorter trajectory, the first index of the minimum of |t_long - t|, kept
// within max_diff. Returns (short index, long index) pairs.
std::vector<std::pair<size_t, size_t>> ArgminPairs(const Trajectory& shorter,
                                                   const Trajectory& longer,
                                                   int64_t max_diff_ns) {
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t i = 0; i < shorter.size(); ++i) {
    size_t best = 0;
    for (size_t j = 1; j < longer.size(); ++j) {
      if (std::llabs(longer[j].t_ns - shorter[i].t_ns) <
          std::llabs(longer[best].t_ns - shorter[i].t_ns)) {
        best = j;
      }
    }
    if (std::llabs(longer[best].t_ns - shorter[i].t_ns) <= max_diff_ns) {
      pairs.emplace_back(i, best);
    }
  }
  return pairs;
}

TEST(Association, RepeatedStampsArePairedAsEvoPairsThem) {
  // Ground truth (longer) with repeats: of the poses at the nearest stamp the
  // first in the file is taken. Estimate (walked) with a repeat: both of its
  // poses are paired.
  const Trajectory gt =
      AtStamps({0, 10 * kMs, 10 * kMs, 10 * kMs, 20 * kMs, 20 * kMs, 30 * kMs});
  const Trajectory est = AtStamps({9 * kMs, 12 * kMs, 12 * kMs, 21 * kMs});
  const Association a = Associate(est, gt, {0.010});
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a.ground_truth[0].p_w_b.x(), 1.0);  // the first pose at 10 ms
  EXPECT_EQ(a.ground_truth[1].p_w_b.x(), 1.0);
  EXPECT_EQ(a.ground_truth[2].p_w_b.x(), 1.0);
  EXPECT_EQ(a.ground_truth[3].p_w_b.x(), 4.0);  // the first pose at 20 ms
  EXPECT_EQ(a.estimate[1].p_w_b.x(), 1.0);
  EXPECT_EQ(a.estimate[2].p_w_b.x(), 2.0);

  // Against the brute-force rule on many random stamp lists with repeats,
  // either side the longer one.
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> step(0, 3);  // 0: a repeat
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<int64_t> a_ns, b_ns;
    int64_t ta = 0, tb = 2 * kMs;
    for (int i = 0; i < 20 + trial % 7; ++i)
      a_ns.push_back(ta += step(rng) * 4 * kMs);
    for (int i = 0; i < 20; ++i) b_ns.push_back(tb += step(rng) * 5 * kMs);
    const Trajectory est = AtStamps(a_ns), truth = AtStamps(b_ns);
    const Association r = Associate(est, truth, {0.006});
    const bool walk_est = est.size() <= truth.size();
    const auto expected = walk_est ? ArgminPairs(est, truth, 6 * kMs)
                                   : ArgminPairs(truth, est, 6 * kMs);
    ASSERT_EQ(r.size(), expected.size()) << trial;
    for (size_t k = 0; k < expected.size(); ++k) {
      const size_t e = walk_est ? expected[k].first : expected[k].second;
      const size_t g = walk_est ? expected[k].second : expected[k].first;
      ASSERT_EQ(r.estimate[k].p_w_b.x(), static_cast<double>(e)) << trial;
      ASSERT_EQ(r.ground_truth[k].p_w_b.x(), static_cast<double>(g)) << trial;
    }
  }
}

TEST(Association, ByIndexPairsLineWithLineAndNeedsEqualCounts) {
  const Trajectory gt = AtStamps({0, 1, 2});
  const Association a = AssociateByIndex(AtStamps({7, 8, 9}), gt);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a.estimate[2].t_ns, 9);
  EXPECT_EQ(a.ground_truth[2].t_ns, 2);
  EXPECT_THROW(AssociateByIndex(AtStamps({7, 8}), gt), std::invalid_argument);
}

TEST(Association, RejectsUnsortedStampsAndBadMaxDiff) {
  const Trajectory sorted = AtStamps({0, 5 * kMs});
  const Trajectory unsorted = AtStamps({5 * kMs, 4 * kMs});
  EXPECT_THROW(Associate(unsorted, sorted), std::invalid_argument);
  EXPECT_THROW(Associate(sorted, unsorted), std::invalid_argument);
  EXPECT_THROW(Associate(sorted, sorted, {-0.1}), std::invalid_argument);
}

// vio_replay reads the ground truth a state at a time and keeps only the
// state nearest each estimate pose: associating with those must give the
// pairs of the whole ground truth, ties (an estimate stamp half-way between
// two states) and poses before the first and after the last state included.
TEST(Association, NearestGroundTruthPairsAsTheWholeDoes) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int64_t> gap(1, 6);  // [ms]
  std::uniform_int_distribution<int> repeat(0, 3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<int64_t> gt_ns, est_ns;
    int64_t t = 0;
    for (int i = 0; i < 200; ++i) gt_ns.push_back(t += 2 * gap(rng) * kMs);
    // Fewer estimates, from before the first state to past the last, on
    // whole ms so that some lie exactly half-way; some stamps repeat.
    for (int64_t e = -30 * kMs; e < t + 30 * kMs; e += 4 * gap(rng) * kMs) {
      for (int r = repeat(rng) == 0 ? 2 : 1; r > 0; --r) est_ns.push_back(e);
    }
    const Trajectory estimate = AtStamps(est_ns);
    const Trajectory gt_poses = AtStamps(gt_ns);
    NearestGroundTruth nearest(estimate);
    for (const StampedPose& p : gt_poses) {
      StampedState s;
      s.t_ns = p.t_ns;
      s.p_w_b = p.p_w_b;
      nearest.Add(s);
    }
    ASSERT_EQ(nearest.states(), static_cast<int64_t>(gt_ns.size()));
    Trajectory kept;
    for (const StampedState& s : nearest.Take()) kept.push_back(PoseOf(s));
    ASSERT_EQ(kept.size(), estimate.size());
    ASSERT_LE(estimate.size(), gt_poses.size());  // as at 20 Hz against 200
    for (double max_diff : {0.001, 0.01}) {
      const Association whole = Associate(estimate, gt_poses, {max_diff});
      const Association few = Associate(estimate, kept, {max_diff});
      ASSERT_EQ(few.size(), whole.size()) << "trial " << trial;
      for (size_t i = 0; i < whole.size(); ++i) {
        EXPECT_EQ(few.estimate[i].p_w_b.x(), whole.estimate[i].p_w_b.x());
        EXPECT_EQ(few.ground_truth[i].t_ns, whole.ground_truth[i].t_ns);
        EXPECT_EQ(few.ground_truth[i].p_w_b.x(),
                  whole.ground_truth[i].p_w_b.x());
      }
    }
  }
}

TEST(Association, NearestGroundTruthRefusesDisorder) {
  const Trajectory estimate = AtStamps({1, 2});
  NearestGroundTruth nearest(estimate);
  StampedState s;
  s.t_ns = 5;
  nearest.Add(s);
  EXPECT_THROW(nearest.Add(s), std::invalid_argument);
  EXPECT_THROW(NearestGroundTruth(AtStamps({2, 1})), std::invalid_argument);
}

}  // namespace
}  // namespace vio
