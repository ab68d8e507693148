// Fuzzes the ADVIO import's CSV readers (rawlog_io/advio_import.h): the input holds, separated by
// lines "%%", iphone/frames.csv, accelerometer.csv, gyro.csv and, when there is a fourth part,
// ground-truth/pose.csv of a folder advio-05. They are read, the accelerometer's units and sign
// detected and the two IMU streams merged before the video is opened; there is none, so a
// complete read ends in the InputError "frames.mov: file not found" and nothing is written. Any
// other exception, a crash or a sanitizer report is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "rawlog_io/advio_import.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;
namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile input(data, size, "input");
  const fs::path dir = fs::path(input.path()).parent_path() / "advio-05";
  fs::create_directories(dir / "iphone");
  const std::string text(reinterpret_cast<const char*>(data), size);
  const char* files[] = {"iphone/frames.csv", "iphone/accelerometer.csv", "iphone/gyro.csv",
                         "ground-truth/pose.csv"};
  const std::string separator = "\n%%\n";
  size_t begin = 0;
  for (const char* file : files) {
    if (begin > text.size()) break;
    const size_t end = std::min(text.find(separator, begin), text.size());
    fs::create_directories((dir / file).parent_path());
    std::ofstream(dir / file, std::ios::binary) << text.substr(begin, end - begin);
    begin = end + separator.size();
  }
  fuzz::readExpectingOnlyInputError([&] {
    AdvioImportOptions opt;
    opt.sequence_dir = dir.string();
    opt.output_rawlog = (dir.parent_path() / "out.rawlog").string();
    importAdvio(opt);
  });
  return 0;
}
