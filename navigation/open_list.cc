#include "navigation/open_list.h"

namespace vio {

void OpenList::Reset(uint64_t first_f, uint64_t span) {
  // The keys alive lie in [k, k + span] (k the last key out), which touches
  // at most (span >> shift_) + 2 buckets: fewer than the ring's kBuckets, so
  // no two alive keys a ring apart share a bucket.
  shift_ = 0;
  while ((span >> shift_) + 2 > kBuckets) ++shift_;
  for (int w = 0; w < kWords; ++w) {
    for (uint64_t m = mask_[w]; m != 0; m &= m - 1) {
      buckets_[64 * w + __builtin_ctzll(m)].clear();
    }
    mask_[w] = 0;
  }
  size_ = 0;
  current_ = Bucket(first_f);
}

void OpenList::Advance() {
  // The next set bit after the current bucket in ring order (there is one:
  // the list is not empty and the current bucket is).
  int w = current_ >> 6;
  uint64_t bits = mask_[w] & (~uint64_t{0} << (current_ & 63));
  while (bits == 0) {
    w = (w + 1) % kWords;
    bits = mask_[w];
  }
  current_ = 64 * w + __builtin_ctzll(bits);
  std::vector<Entry>& bucket = buckets_[current_];
  std::make_heap(bucket.begin(), bucket.end(), LaterOut());
}

}  // namespace vio
