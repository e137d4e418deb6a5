// mav0/camN/data.csv, the image list (dataset/euroc_reader.h:
// ReadEurocImageList). The listed images are looked up in an empty folder,
// so every data line is a missing image: the count must say so. Any refusal
// is a DatasetError naming the file.

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("cam0_data.csv");
  static vio::fuzz::ScratchFile folder("cam0_images");
  static const bool made = std::filesystem::create_directories(folder.path());
  (void)made;
  const std::string& path = file.Write(data, size);
  try {
    int missing = -1;
    const std::vector<vio::ImageEntry> images =
        vio::ReadEurocImageList(path, folder.path(), &missing);
    vio::fuzz::Require(images.empty(), "an image found in an empty folder");
    vio::fuzz::Require(missing >= 0, "the missing count was not set");
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
