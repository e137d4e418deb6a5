#ifndef VIO_TEST_TESTING_GLITCHY_IMU_LINES_H_
#define VIO_TEST_TESTING_GLITCHY_IMU_LINES_H_

// Stamp faults of every kind the IMU stamp filter deals with, put at random
// into IMU lines, for the tests that hold the bounded filter equal to the
// whole-file one (imu_stamp_filter_test, euroc_csv_stream_test); and the
// lines of an IMU file as plain values.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "dataset/csv.h"
#include "dataset/imu_stamp_filter.h"

namespace vio {
namespace testing {

// Inserts or alters lines of `lines` (in file order) at random: exact
// repeats, repeated stamps with other values, samples from the past, single
// stamps and runs of 2-3 stamps far in the future, swapped neighbours, a
// clock stepping back, stamps equal to one two lines back. `rate` is the
// chance of a fault per line. Line numbers are renumbered 2, 3, ... (a
// header on line 1).
inline void InjectStampGlitches(std::vector<ImuLine>* lines, double rate,
                                std::mt19937* rng) {
  std::uniform_real_distribution<double> chance(0.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 8);
  std::uniform_int_distribution<int64_t> ms(1, 60);
  std::vector<ImuLine> out;
  out.reserve(lines->size() * 2);
  for (size_t k = 0; k < lines->size(); ++k) {
    ImuLine l = (*lines)[k];
    if (chance(*rng) >= rate || out.empty()) {
      out.push_back(l);
      continue;
    }
    const ImuLine previous = out.back();
    switch (kind(*rng)) {
      case 0:  // the previous line again
        out.push_back(previous);
        out.push_back(l);
        break;
      case 1: {  // the previous stamp with other values
        ImuLine other = previous;
        other.sample.gyr.x() += 0.5;
        out.push_back(other);
        out.push_back(l);
        break;
      }
      case 2:  // from the past
        l.sample.t_ns = previous.sample.t_ns - ms(*rng) * 1000000;
        out.push_back(l);
        break;
      case 3:  // one stamp into the future
        l.sample.t_ns += ms(*rng) * 100000000;
        out.push_back(l);
        break;
      case 4: {  // a run of 2 or 3 into the future
        const int run = 2 + static_cast<int>(ms(*rng) % 2);
        const int64_t ahead = ms(*rng) * 100000000;
        for (int r = 0; r < run && k < lines->size(); ++r, ++k) {
          ImuLine g = (*lines)[k];
          g.sample.t_ns += ahead;
          out.push_back(g);
        }
        --k;
        break;
      }
      case 5:  // swapped with the next
        if (k + 1 < lines->size()) {
          out.push_back((*lines)[k + 1]);
          out.push_back(l);
          ++k;
        } else {
          out.push_back(l);
        }
        break;
      case 6: {  // the clock steps back for the rest of the file
        const int64_t back = ms(*rng) * 10000000;
        for (size_t j = k; j < lines->size(); ++j) {
          (*lines)[j].sample.t_ns -= back;
        }
        out.push_back((*lines)[k]);
        break;
      }
      case 7:  // the stamp of two lines back
        l.sample.t_ns = out.size() >= 2 ? out[out.size() - 2].sample.t_ns
                                        : previous.sample.t_ns;
        out.push_back(l);
        break;
      default:  // the previous values at this stamp (not a repeat)
        l.sample.acc = previous.sample.acc;
        l.sample.gyr = previous.sample.gyr;
        out.push_back(l);
        break;
    }
  }
  for (size_t i = 0; i < out.size(); ++i) out[i].line = static_cast<int>(i) + 2;
  *lines = std::move(out);
}

// Every data line of an imu0/data.csv as read (no filter, no check of the
// stamps' order), with its line number.
inline std::vector<ImuLine> ReadImuLines(const std::string& path) {
  CsvReader csv(path);
  std::vector<ImuLine> lines;
  while (csv.Next()) {
    ImuLine l;
    l.sample.t_ns = csv.Int64(0);
    l.sample.gyr = {csv.Double(1), csv.Double(2), csv.Double(3)};
    l.sample.acc = {csv.Double(4), csv.Double(5), csv.Double(6)};
    l.line = csv.line();
    lines.push_back(l);
  }
  return lines;
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_GLITCHY_IMU_LINES_H_
