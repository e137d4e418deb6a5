#include "dataset/euroc_image_writer.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"

namespace vio {

EurocImageWriter::EurocImageWriter(const std::string& camera_folder)
    : folder_(JoinPath(camera_folder, "data")),
      list_path_(JoinPath(camera_folder, "data.csv")) {
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  if (ec) throw DatasetError(folder_ + ": cannot create the folder");
  list_.open(list_path_);
  if (!list_) {
    throw DatasetError(list_path_ + ": cannot open the file for writing");
  }
  list_ << "#timestamp [ns],filename\n";
}

void EurocImageWriter::Write(int64_t t_ns, const cv::Mat& image) {
  if (image.empty() || image.type() != CV_8UC1) {
    throw DatasetError(folder_ + ": image at " + std::to_string(t_ns) +
                       " ns is not 8-bit grey");
  }
  if (images_ > 0 && t_ns <= last_t_ns_) {
    throw DatasetError(list_path_ + ": stamp " + std::to_string(t_ns) +
                       " is not after the previous one (" +
                       std::to_string(last_t_ns_) + ")");
  }
  const std::string name = std::to_string(t_ns) + ".png";
  const std::string path = JoinPath(folder_, name);
  // Fast compression: noise makes the images hardly compressible anyway.
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  bool ok = false;
  try {
    ok = cv::imwrite(path, image, params);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw DatasetError(path + ": cannot write the image");
  list_ << t_ns << ',' << name << '\n';
  last_t_ns_ = t_ns;
  ++images_;
}

void EurocImageWriter::Close() {
  list_.close();
  if (!list_) throw DatasetError(list_path_ + ": write failed");
}

}  // namespace vio
