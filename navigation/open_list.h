#ifndef VIO_NAVIGATION_OPEN_LIST_H_
#define VIO_NAVIGATION_OPEN_LIST_H_

// The A* open list (navigation/astar.h): entries come out smallest f first
// and, among equal f, largest g first. It is the notes' binary heap cut into
// buckets of f:
//   - the bucket holding the smallest f is a binary heap (std::push_heap /
//     std::pop_heap with the order above);
//   - the buckets ahead of it are unordered lists: a push there is an
//     append, and a bucket becomes a heap (std::make_heap) when it is reached.
// A push costs O(1) or a heap push within one bucket, a pop a heap pop within
// one bucket, instead of O(log n) in a heap of the whole open list.
//
// This relies on what A* with a consistent heuristic guarantees, and the
// caller must too: keys are integers (fixed point), no key pushed is below
// the last key taken out, nor above it by more than `span` (f of a successor
// exceeds f of the node expanded by at most twice the step cost). The keys
// alive then lie in fewer than kBuckets consecutive buckets, so the buckets
// form a ring indexed by key / width mod kBuckets, and the next bucket with
// entries is the next set bit of a 64-bit mask.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vio {

class OpenList {
 public:
  struct Entry {
    Entry() = default;
    Entry(uint64_t f_, uint32_t g_, int32_t node_)
        : f(f_), g(g_), node(node_) {}
    uint64_t f;    // g + h, fixed point
    uint32_t g;    // g, fixed point, its high 32 bits: breaks ties of f
    int32_t node;  // 16 bytes in all
  };

  static constexpr int kBuckets = 1024;

  // An empty list for keys from first_f up to the largest key taken out plus
  // `span` (>= 1), which sets the width of a bucket.
  void Reset(uint64_t first_f, uint64_t span);

  bool empty() const { return size_ == 0; }

  // Requires f >= the last key taken out, and no more than `span` above it.
  // (The fields are stored in place: an Entry built on the stack and copied
  // would be read back as 16 bytes right after three narrower stores, which
  // stalls store-to-load forwarding.)
  void Push(uint64_t f, uint32_t g, int32_t node) {
    const int b = Bucket(f);
    std::vector<Entry>& bucket = buckets_[b];
    bucket.emplace_back(f, g, node);
    if (b == current_) std::push_heap(bucket.begin(), bucket.end(), LaterOut());
    mask_[b >> 6] |= uint64_t{1} << (b & 63);
    ++size_;
  }

  // The smallest f, and among those the largest g. Requires !empty().
  Entry Pop() {
    if (buckets_[current_].empty()) Advance();
    std::vector<Entry>& bucket = buckets_[current_];
    std::pop_heap(bucket.begin(), bucket.end(), LaterOut());
    const Entry e = bucket.back();
    bucket.pop_back();
    if (bucket.empty())
      mask_[current_ >> 6] &= ~(uint64_t{1} << (current_ & 63));
    --size_;
    return e;
  }

 private:
  static constexpr int kWords = kBuckets / 64;
  static_assert(kBuckets % 64 == 0, "the occupied buckets are 64-bit words");

  // std::push_heap keeps the "largest" on top, so an entry is "less" when it
  // should come out later: a larger f, or an equal f with a smaller g.
  struct LaterOut {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.f > b.f || (a.f == b.f && a.g < b.g);
    }
  };

  int Bucket(uint64_t f) const {
    return static_cast<int>((f >> shift_) & (kBuckets - 1));
  }

  // Moves to the next bucket with entries (the ring's next set bit) and
  // makes it a heap.
  void Advance();

  std::vector<Entry> buckets_[kBuckets];
  uint64_t mask_[kWords] = {};  // bit b: buckets_[b] has entries
  int64_t size_ = 0;
  int current_ = 0;  // the bucket with the smallest keys: a heap
  int shift_ = 0;    // a bucket holds keys [k, k + 2^shift_)
};

}  // namespace vio

#endif  // VIO_NAVIGATION_OPEN_LIST_H_
