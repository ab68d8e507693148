// Fuzzes PngGrayDecoder (rawlog_io/png_gray_decoder.h) against OpenCV's libpng path: whatever it
// decodes is an 8-bit image and, when OpenCV decodes the same bytes as 8-bit grayscale too, holds
// the same pixels. Corrupt or other input must come back as a status, never a crash. Mutations
// break chunk CRCs, which would stop almost every input at the first check: inputs whose first
// byte is odd get their CRCs repaired first, so the fuzzer reaches inflating and unfiltering.
#include <libdeflate.h>
#include <cstddef>
#include <cstdint>

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "rawlog_io/png_gray_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

namespace {

/// `png` with the CRC of every complete chunk after the signature recomputed.
void repairChunkCrcs(std::vector<uint8_t>& png) {
  auto be32 = [&png](size_t at) {
    return uint32_t(png[at]) << 24 | uint32_t(png[at + 1]) << 16 | uint32_t(png[at + 2]) << 8 |
           uint32_t(png[at + 3]);
  };
  for (size_t pos = 8; pos + 12 <= png.size();) {
    const size_t length = be32(pos);
    if (length > png.size() - pos - 12) return;
    const uint32_t crc = libdeflate_crc32(0, &png[pos + 4], 4 + length);
    for (int i = 0; i < 4; ++i) png[pos + 8 + length + size_t(i)] = uint8_t(crc >> (24 - 8 * i));
    pos += 12 + length;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* input, size_t size) {
  if (size == 0) return 0;
  std::vector<uint8_t> png(input + 1, input + size);
  if (input[0] & 1) repairChunkCrcs(png);
  static PngGrayDecoder decoder;  // buffers reused across inputs, as in a run
  cv::Mat ours;
  std::string why;
  if (decoder.decode(png.data(), png.size(), ours, why) != PngGrayDecoder::Status::Decoded)
    return 0;
  fuzz::require(!ours.empty() && ours.type() == CV_8UC1, "decoded image not 8-bit grayscale");
  const cv::Mat theirs = cv::imdecode(png, cv::IMREAD_UNCHANGED);
  if (theirs.empty() || theirs.type() != CV_8UC1) return 0;
  fuzz::require(theirs.size() == ours.size() && cv::norm(theirs, ours, cv::NORM_INF) == 0,
                "pixels differ from OpenCV's");
  return 0;
}
