#ifndef VIO_DATASET_EUROC_CSV_STREAM_H_
#define VIO_DATASET_EUROC_CSV_STREAM_H_

// The two EuRoC files that grow with a sequence's length and are read in
// order, imu0/data.csv and camN/data.csv, read a line at a time, so that a
// replay holds only the line at hand however long the sequence is
// (vio_replay). Each gives exactly what the whole-file readers of
// dataset/euroc_reader.h give (those are loops over these), with the same
// errors, at the line that causes them: a DatasetError naming the file and
// the line.

#include <cstdint>
#include <memory>
#include <string>

#include "dataset/imu_stamp_filter.h"
#include "preintegration/imu_types.h"

namespace vio {

class CsvReader;  // dataset/csv.h

// One image listed in camN/data.csv whose file exists.
struct ImageEntry {
  int64_t t_ns = 0;  // camera stamp [ns]
  std::string path;  // the image file: <camN>/data/<filename>
};

// imu0/data.csv: t [ns], w_x, w_y, w_z [rad/s], a_x, a_y, a_z [m/s^2].
// Strict (report null): stamps must strictly increase, or DatasetError.
// Otherwise repeated and out-of-order stamps are dropped and counted in
// *report (dataset/imu_stamp_filter.h, one line of look-ahead). Non-finite
// values are errors either way. A file without any sample is an error when
// its end is reached.
class ImuCsvStream {
 public:
  // Throws DatasetError when the file is missing or cannot be opened.
  ImuCsvStream(const std::string& path, ImuStampReport* report);
  ~ImuCsvStream();

  // The next sample, in strictly increasing stamp order; false at the end
  // (and on every call after it).
  bool Next(ImuSample* sample);

  const std::string& path() const { return path_; }

 private:
  bool ReadLine(ImuLine* line);

  std::string path_;
  std::unique_ptr<CsvReader> csv_;
  bool strict_;
  ImuStampReport unused_report_;  // the filter's counts when strict
  ImuStampFilter filter_;
  bool any_line_ = false;
  int64_t previous_t_ns_ = 0;  // strict: the last stamp read
  bool finished_ = false;
};

// camN/data.csv: t [ns], filename; stamps strictly increasing. The images
// whose file is missing from `image_folder` are skipped and counted.
class ImageListStream {
 public:
  // Throws DatasetError when the list is missing or cannot be opened.
  ImageListStream(const std::string& path, const std::string& image_folder);
  ~ImageListStream();

  // The next listed image whose file exists; false at the end (and on every
  // call after it).
  bool Next(ImageEntry* entry);

  // Listed images skipped so far because their file is missing.
  int missing() const { return missing_; }

 private:
  std::string image_folder_;
  std::unique_ptr<CsvReader> csv_;
  int missing_ = 0;
  bool any_line_ = false;
  int64_t previous_t_ns_ = 0;
};

}  // namespace vio

#endif  // VIO_DATASET_EUROC_CSV_STREAM_H_
