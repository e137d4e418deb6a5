#ifndef VIO_DATASET_EUROC_IMAGE_WRITER_H_
#define VIO_DATASET_EUROC_IMAGE_WRITER_H_

// Writes one camera's images in the EuRoC ASL layout, as EuRoC's own
// folders hold them, so that the reader (dataset/euroc_reader.h) and every
// EuRoC tool read them like a recorded sequence:
//
//   <camera folder>/data/<t_ns>.png   8-bit grey PNG
//   <camera folder>/data.csv          "#timestamp [ns],filename" then one
//                                     "<t_ns>,<t_ns>.png" row per image

#include <cstdint>
#include <fstream>
#include <opencv2/core.hpp>
#include <string>

namespace vio {

class EurocImageWriter {
 public:
  // Creates <camera_folder>/data/ and data.csv. Throws DatasetError naming
  // the path when it cannot.
  explicit EurocImageWriter(const std::string& camera_folder);

  // Writes `image` (8-bit, one channel) as <t_ns>.png and its row. Throws
  // DatasetError when the image is not 8-bit grey, the stamp is not after
  // the previous one, or a file cannot be written.
  void Write(int64_t t_ns, const cv::Mat& image);

  // Flushes data.csv; throws DatasetError when that fails.
  void Close();

  int64_t images() const { return images_; }

 private:
  std::string folder_;
  std::string list_path_;
  std::ofstream list_;
  int64_t images_ = 0;
  int64_t last_t_ns_ = 0;
};

}  // namespace vio

#endif  // VIO_DATASET_EUROC_IMAGE_WRITER_H_
