#pragma once
// Decodes 8-bit grayscale, non-interlaced PNG (what the rawlog writer and the simulator write, and
// most camera datasets) with libdeflate: ~3x faster than OpenCV's libpng path on our frames, which
// made PNG decoding a fifth of a frame's time. Every other PNG variant is left to OpenCV.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

struct libdeflate_decompressor;

namespace rpvio {

class PngGrayDecoder {
 public:
  enum class Status {
    Decoded,       ///< `image` holds the pixels
    OtherVariant,  ///< not a PNG, or colour, palette, 16-bit, interlaced, transparency: use OpenCV
    Corrupt,       ///< truncated, bad CRC or checksum, sizes that disagree: `why` says which
  };

  PngGrayDecoder();
  ~PngGrayDecoder();
  PngGrayDecoder(const PngGrayDecoder&) = delete;
  PngGrayDecoder& operator=(const PngGrayDecoder&) = delete;

  /// `image` gets a new CV_8UC1 buffer when Decoded (earlier results stay valid); the decoder's
  /// own buffers are kept between calls.
  Status decode(const uint8_t* data, size_t size, cv::Mat& image, std::string& why);

 private:
  struct FreeDecompressor {
    void operator()(libdeflate_decompressor* d) const;
  };
  std::unique_ptr<libdeflate_decompressor, FreeDecompressor> inflater_;
  std::vector<uint8_t> compressed_;  // the IDAT chunks, concatenated
  std::vector<uint8_t> filtered_;    // inflated rows, each led by its filter type
  std::vector<uint8_t> zero_row_;    // the row "above" the first one
};

}  // namespace rpvio
