#ifndef VIO_TEST_TESTING_TEMP_FOLDER_H_
#define VIO_TEST_TESTING_TEMP_FOLDER_H_

// A fresh folder under the system's temporary directory, named after the
// running test and removed when the object dies; with a helper that writes
// text files (creating their parent folders), for fixture datasets.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace vio {
namespace testing {

class TempFolder {
 public:
  TempFolder() {
    const ::testing::TestInfo* info =
        ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "tcvio_";
    if (info != nullptr) {
      name += std::string(info->test_suite_name()) + "_" + info->name();
    }
    name += "_" + std::to_string(::getpid());
    path_ = (std::filesystem::temp_directory_path() / name).string();
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  const std::string& path() const { return path_; }

  // path() + "/" + relative.
  std::string Path(const std::string& relative) const {
    return (std::filesystem::path(path_) / relative).string();
  }

  // Writes `text` to path()/relative, creating the parent folders.
  void Write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path file = std::filesystem::path(path_) / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }

  void Remove(const std::string& relative) const {
    std::filesystem::remove_all(std::filesystem::path(path_) / relative);
  }

 private:
  std::string path_;
};

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_TEMP_FOLDER_H_
