#include "rawlog_io/png_gray_decoder.h"

#include <libdeflate.h>
#include <cstdlib>
#include <cstring>

namespace rpvio {

namespace {

constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
// Deflate expands at most ~1032:1; a header claiming more pixels than that is corrupt (and must
// not make us allocate what it claims).
constexpr size_t kMaxDeflateRatio = 1032;
constexpr uint32_t kMaxSide = 0x7fffffff;  // PNG spec §11.2.2

uint32_t bigEndian32(const uint8_t* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

bool isChunk(const uint8_t* type, const char* name) { return std::memcmp(type, name, 4) == 0; }

// PNG spec §5.3: chunk types are four ASCII letters.
bool isValidChunkType(const uint8_t* type) {
  for (int i = 0; i < 4; ++i)
    if (!((type[i] >= 'A' && type[i] <= 'Z') || (type[i] >= 'a' && type[i] <= 'z'))) return false;
  return true;
}

// PNG spec §9.4: the predictor closest to left + up - upper_left, ties to left then up.
inline int paeth(int left, int up, int upper_left) {
  const int pa = std::abs(up - upper_left);
  const int pb = std::abs(left - upper_left);
  const int pc = std::abs(left + up - 2 * upper_left);
  return pa <= pb && pa <= pc ? left : pb <= pc ? up : upper_left;
}

// PNG spec §9.2 for one byte per pixel: out = in + predictor(left, up, upper-left), modulo 256.
bool unfilterRow(uint8_t type, const uint8_t* in, const uint8_t* up, uint8_t* out, size_t width) {
  switch (type) {
    case 0:
      std::memcpy(out, in, width);
      return true;
    case 1: {
      uint8_t left = 0;
      for (size_t x = 0; x < width; ++x) out[x] = left = uint8_t(in[x] + left);
      return true;
    }
    case 2:
      for (size_t x = 0; x < width; ++x) out[x] = uint8_t(in[x] + up[x]);
      return true;
    case 3: {
      int left = 0;
      for (size_t x = 0; x < width; ++x)
        out[x] = uint8_t(left = uint8_t(in[x] + ((left + up[x]) >> 1)));
      return true;
    }
    case 4: {
      int left = 0, upper_left = 0;
      for (size_t x = 0; x < width; ++x) {
        left = uint8_t(in[x] + paeth(left, up[x], upper_left));
        out[x] = uint8_t(left);
        upper_left = up[x];
      }
      return true;
    }
    default:
      return false;
  }
}

}  // namespace

void PngGrayDecoder::FreeDecompressor::operator()(libdeflate_decompressor* d) const {
  libdeflate_free_decompressor(d);
}

PngGrayDecoder::PngGrayDecoder() : inflater_(libdeflate_alloc_decompressor()) {
  if (!inflater_) throw std::bad_alloc();
}

PngGrayDecoder::~PngGrayDecoder() = default;

PngGrayDecoder::Status PngGrayDecoder::decode(const uint8_t* data, size_t size, cv::Mat& image,
                                              std::string& why) {
  auto corrupt = [&why](const std::string& reason) {
    why = reason;
    return Status::Corrupt;
  };
  if (size < sizeof(kSignature) || std::memcmp(data, kSignature, sizeof(kSignature)) != 0)
    return Status::OtherVariant;

  // Chunks (PNG spec §5.3): length, type, data, CRC of type and data.
  uint32_t width = 0, height = 0;
  bool header_seen = false, end_seen = false;
  compressed_.clear();
  for (size_t pos = sizeof(kSignature); !end_seen;) {
    if (size - pos < 12) return corrupt("truncated at byte " + std::to_string(pos));
    const uint32_t length = bigEndian32(data + pos);
    const uint8_t* type = data + pos + 4;
    const uint8_t* body = type + 4;
    if (length > size - pos - 12)
      return corrupt("truncated in the chunk at byte " + std::to_string(pos));
    if (!isValidChunkType(type))
      return corrupt("invalid chunk type at byte " + std::to_string(pos));
    if (libdeflate_crc32(0, type, 4 + size_t(length)) != bigEndian32(body + length))
      return corrupt("CRC mismatch in the chunk at byte " + std::to_string(pos));
    if (!header_seen) {
      if (!isChunk(type, "IHDR") || length != 13) return corrupt("no IHDR chunk first");
      width = bigEndian32(body);
      height = bigEndian32(body + 4);
      const uint8_t bit_depth = body[8], colour = body[9], compression = body[10],
                    filter = body[11], interlace = body[12];
      if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide || compression != 0 ||
          filter != 0 || interlace > 1)
        return corrupt("invalid IHDR");
      if (bit_depth != 8 || colour != 0 || interlace != 0) return Status::OtherVariant;
      header_seen = true;
    } else if (isChunk(type, "IDAT")) {
      compressed_.insert(compressed_.end(), body, body + length);
    } else if (isChunk(type, "IEND")) {
      end_seen = true;
    } else if (isChunk(type, "tRNS") || (type[0] & 0x20) == 0) {
      return Status::OtherVariant;  // transparency, or a critical chunk (a palette, ...)
    }
    pos += 12 + size_t(length);
  }

  const size_t row_bytes = size_t(width) + 1;
  const size_t filtered_bytes = row_bytes * height;  // < 2^62: both sides are below 2^31
  if (filtered_bytes > compressed_.size() * kMaxDeflateRatio)
    return corrupt("too little image data for " + std::to_string(width) + "x" +
                   std::to_string(height) + " pixels");
  filtered_.resize(filtered_bytes);
  size_t inflated = 0;
  const libdeflate_result result =
      libdeflate_zlib_decompress(inflater_.get(), compressed_.data(), compressed_.size(),
                                 filtered_.data(), filtered_.size(), &inflated);
  if (result == LIBDEFLATE_INSUFFICIENT_SPACE) return corrupt("more image data than pixels");
  if (result != LIBDEFLATE_SUCCESS) return corrupt("compressed image data corrupt");
  if (inflated != filtered_bytes) return corrupt("image data ends early");

  cv::Mat out(int(height), int(width), CV_8UC1);
  zero_row_.assign(width, 0);
  const uint8_t* up = zero_row_.data();
  for (uint32_t y = 0; y < height; ++y) {
    const uint8_t* row = filtered_.data() + y * row_bytes;
    if (!unfilterRow(row[0], row + 1, up, out.ptr(int(y)), width))
      return corrupt("unknown filter type " + std::to_string(row[0]) + " in row " +
                     std::to_string(y));
    up = out.ptr(int(y));
  }
  image = out;
  return Status::Decoded;
}

}  // namespace rpvio
