// Fuzzes PngGrayDecoder (rawlog_io/png_gray_decoder.h) against OpenCV's libpng path: whatever it
// decodes is an 8-bit image and, when OpenCV decodes the same bytes as 8-bit grayscale too, holds
// the same pixels. Corrupt or other input must come back as a status, never a crash.
#include <cstddef>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>

#include "rawlog_io/png_gray_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static PngGrayDecoder decoder;  // buffers reused across inputs, as in a run
  cv::Mat ours;
  std::string why;
  if (decoder.decode(data, size, ours, why) != PngGrayDecoder::Status::Decoded) return 0;
  fuzz::require(!ours.empty() && ours.type() == CV_8UC1, "decoded image not 8-bit grayscale");
  const cv::Mat bytes(1, int(size), CV_8UC1, const_cast<uint8_t*>(data));
  const cv::Mat theirs = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (theirs.empty() || theirs.type() != CV_8UC1) return 0;
  fuzz::require(theirs.size() == ours.size() && cv::norm(theirs, ours, cv::NORM_INF) == 0,
                "pixels differ from OpenCV's");
  return 0;
}
