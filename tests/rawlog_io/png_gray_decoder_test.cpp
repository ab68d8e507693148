// PngGrayDecoder: the pixels OpenCV decodes, for every PNG filter type; other variants left to
// OpenCV; corrupt files refused with a reason, without allocating what a bad header claims.
#include "rawlog_io/png_gray_decoder.h"

#include <gtest/gtest.h>
#include <libdeflate.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "common/input_error.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

using Bytes = std::vector<uint8_t>;
using Status = PngGrayDecoder::Status;

void putBigEndian32(Bytes& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
}

void putChunk(Bytes& out, const char* type, const Bytes& body) {
  putBigEndian32(out, uint32_t(body.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), body.begin(), body.end());
  putBigEndian32(out, uint32_t(libdeflate_crc32(0, out.data() + start, out.size() - start)));
}

int paethPredictor(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/// Row y filtered with `type` (PNG spec §9.2, written from the spec's own formulation).
Bytes filterRow(const cv::Mat& img, int y, uint8_t type) {
  Bytes row{type};
  for (int x = 0; x < img.cols; ++x) {
    const int v = img.at<uint8_t>(y, x);
    const int a = x > 0 ? img.at<uint8_t>(y, x - 1) : 0;
    const int b = y > 0 ? img.at<uint8_t>(y - 1, x) : 0;
    const int c = x > 0 && y > 0 ? img.at<uint8_t>(y - 1, x - 1) : 0;
    const int prediction[5] = {0, a, b, (a + b) / 2, paethPredictor(a, b, c)};
    row.push_back(uint8_t(v - prediction[type % 5]));
  }
  return row;
}

struct PngParts {
  Bytes ihdr, idat;
  Bytes extra_chunk_body;
  const char* extra_chunk = nullptr;
};

/// An 8-bit grayscale PNG of `img` whose row y uses filter type filters[y % size].
PngParts grayPngParts(const cv::Mat& img, const Bytes& filters) {
  PngParts parts;
  putBigEndian32(parts.ihdr, uint32_t(img.cols));
  putBigEndian32(parts.ihdr, uint32_t(img.rows));
  for (uint8_t b : {8, 0, 0, 0, 0})
    parts.ihdr.push_back(b);  // depth, gray, zlib, filter, no interlace
  Bytes raw;
  for (int y = 0; y < img.rows; ++y) {
    const Bytes row = filterRow(img, y, filters[size_t(y) % filters.size()]);
    raw.insert(raw.end(), row.begin(), row.end());
  }
  libdeflate_compressor* c = libdeflate_alloc_compressor(6);
  parts.idat.resize(libdeflate_zlib_compress_bound(c, raw.size()));
  parts.idat.resize(
      libdeflate_zlib_compress(c, raw.data(), raw.size(), parts.idat.data(), parts.idat.size()));
  libdeflate_free_compressor(c);
  return parts;
}

Bytes assemble(const PngParts& parts, size_t idat_pieces = 1) {
  Bytes out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  putChunk(out, "IHDR", parts.ihdr);
  if (parts.extra_chunk) putChunk(out, parts.extra_chunk, parts.extra_chunk_body);
  const size_t piece = (parts.idat.size() + idat_pieces - 1) / idat_pieces;
  for (size_t i = 0; i < parts.idat.size(); i += piece)
    putChunk(out, "IDAT",
             Bytes(parts.idat.begin() + long(i),
                   parts.idat.begin() + long(std::min(parts.idat.size(), i + piece))));
  putChunk(out, "IEND", {});
  return out;
}

/// A textured test image: noise over a gradient, so every predictor has work to do.
cv::Mat testImage(int rows, int cols) {
  cv::Mat img(rows, cols, CV_8UC1);
  cv::RNG rng(7);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      img.at<uint8_t>(y, x) = uint8_t(3 * x + 5 * y + rng.uniform(0, 40));
  return img;
}

Status decode(const Bytes& png, cv::Mat& img, std::string& why) {
  PngGrayDecoder decoder;
  return decoder.decode(png.data(), png.size(), img, why);
}

void expectSamePixels(const cv::Mat& a, const cv::Mat& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.type(), b.type());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

}  // namespace

TEST(PngGrayDecoder, EveryFilterTypeGivesTheImageAndOpenCvsPixels) {
  const cv::Mat img = testImage(23, 37);
  for (const Bytes& filters : {Bytes{0}, Bytes{1}, Bytes{2}, Bytes{3}, Bytes{4},
                               Bytes{0, 1, 2, 3, 4}, Bytes{4, 3, 2, 1, 0, 2}}) {
    const Bytes png = assemble(grayPngParts(img, filters), 3);  // IDAT split in 3 chunks
    cv::Mat ours;
    std::string why;
    ASSERT_EQ(decode(png, ours, why), Status::Decoded) << why;
    expectSamePixels(ours, img);
    expectSamePixels(ours, cv::imdecode(png, cv::IMREAD_UNCHANGED));
  }
}

TEST(PngGrayDecoder, ReadsWhatOpenCvWritesAtEveryLevel) {
  const cv::Mat img = testImage(48, 64);
  for (const std::vector<int>& params :
       {std::vector<int>{},
        {cv::IMWRITE_PNG_COMPRESSION, 0},
        {cv::IMWRITE_PNG_COMPRESSION, 1},
        {cv::IMWRITE_PNG_COMPRESSION, 9},
        {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY}}) {
    std::vector<uint8_t> png;
    ASSERT_TRUE(cv::imencode(".png", img, png, params));
    cv::Mat ours;
    std::string why;
    ASSERT_EQ(decode(png, ours, why), Status::Decoded) << why;
    expectSamePixels(ours, img);
  }
}

TEST(PngGrayDecoder, EachResultHasItsOwnBuffer) {
  PngGrayDecoder decoder;
  const cv::Mat first_img = testImage(10, 12), second_img = 255 - testImage(10, 12);
  const Bytes first = assemble(grayPngParts(first_img, {1}));
  const Bytes second = assemble(grayPngParts(second_img, {4}));
  cv::Mat a, b;
  std::string why;
  ASSERT_EQ(decoder.decode(first.data(), first.size(), a, why), Status::Decoded);
  ASSERT_EQ(decoder.decode(second.data(), second.size(), b, why), Status::Decoded);
  expectSamePixels(a, first_img);
  expectSamePixels(b, second_img);
}

TEST(PngGrayDecoder, OtherVariantsAreLeftToOpenCv) {
  const cv::Mat img = testImage(8, 8);
  std::vector<Bytes> others;
  for (const cv::Mat& m : {cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)), cv::Mat(8, 8, CV_16UC1)}) {
    std::vector<uint8_t> png;
    ASSERT_TRUE(cv::imencode(".png", m, png));
    others.push_back(png);
  }
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", img, jpeg));
  others.push_back(jpeg);
  PngParts interlaced = grayPngParts(img, {0});
  interlaced.ihdr[12] = 1;
  others.push_back(assemble(interlaced));
  PngParts transparent = grayPngParts(img, {0});
  transparent.extra_chunk = "tRNS";
  transparent.extra_chunk_body = {0, 0};
  others.push_back(assemble(transparent));
  for (const Bytes& other : others) {
    cv::Mat out;
    std::string why;
    EXPECT_EQ(decode(other, out, why), Status::OtherVariant);
  }
}

TEST(PngGrayDecoder, AncillaryChunksAreSkipped) {
  const cv::Mat img = testImage(9, 11);
  PngParts parts = grayPngParts(img, {2});
  parts.extra_chunk = "tEXt";
  parts.extra_chunk_body = {'a', 0, 'b'};
  cv::Mat out;
  std::string why;
  ASSERT_EQ(decode(assemble(parts), out, why), Status::Decoded) << why;
  expectSamePixels(out, img);
}

TEST(PngGrayDecoder, CorruptFilesAreRefusedWithAReason) {
  const cv::Mat img = testImage(16, 20);
  const Bytes good = assemble(grayPngParts(img, {0, 1, 2, 3, 4}));
  auto expectCorrupt = [](const Bytes& png, const std::string& reason) {
    cv::Mat out;
    std::string why;
    EXPECT_EQ(decode(png, out, why), Status::Corrupt) << reason;
    EXPECT_NE(why.find(reason), std::string::npos) << why;
    EXPECT_TRUE(out.empty());
  };
  for (size_t cut : {size_t(9), size_t(20), good.size() / 2, good.size() - 1})
    expectCorrupt(Bytes(good.begin(), good.begin() + long(cut)), "truncated");

  Bytes flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  expectCorrupt(flipped, "CRC mismatch");

  PngParts bad_stream = grayPngParts(img, {0});
  bad_stream.idat.back() ^= 0xff;  // zlib's Adler-32 no longer holds (the chunk CRC is recomputed)
  expectCorrupt(assemble(bad_stream), "compressed image data corrupt");

  expectCorrupt(assemble(grayPngParts(img, {5})), "unknown filter type 5 in row 0");

  PngParts bad_type = grayPngParts(img, {0});
  bad_type.extra_chunk = "t1Xt";  // libpng refuses it too
  expectCorrupt(assemble(bad_type), "invalid chunk type at byte 33");

  PngParts taller = grayPngParts(img, {1});
  taller.ihdr[7] = uint8_t(img.rows + 1);  // one row more than the data holds
  expectCorrupt(assemble(taller), "image data ends early");

  PngParts shorter = grayPngParts(img, {1});
  shorter.ihdr[7] = uint8_t(img.rows - 1);
  expectCorrupt(assemble(shorter), "more image data than pixels");

  PngParts empty = grayPngParts(img, {1});
  empty.ihdr[3] = 0;  // width 0
  expectCorrupt(assemble(empty), "invalid IHDR");

  // A header claiming 2^31-1 x 2^31-1 pixels over a few bytes of data: refused before allocating.
  PngParts huge = grayPngParts(img, {1});
  huge.ihdr.clear();
  putBigEndian32(huge.ihdr, 0x7fffffff);
  putBigEndian32(huge.ihdr, 0x7fffffff);
  for (uint8_t b : {8, 0, 0, 0, 0}) huge.ihdr.push_back(b);
  expectCorrupt(assemble(huge), "too little image data");
}

TEST(PngGrayDecoder, RawlogImagesDecodeAsWrittenAndACorruptOneNamesFileAndEntry) {
  test::TempDir dir;
  const std::string path = dir.file("seq.rawlog");
  Calibration calib;
  calib.camera.width = 20;
  calib.camera.height = 16;
  calib.camera.fx = calib.camera.fy = 10;
  const cv::Mat img = testImage(16, 20);
  cv::Mat mask(16, 20, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(0, 8, 20, 8)).setTo(3);
  {
    RawlogWriter writer(path, calib);
    writer.addImage(1.0, img);
    writer.addMask(1.0, mask);
    writer.close();
  }
  std::vector<cv::Mat> loaded;
  {
    RawlogReader reader(path);
    while (auto obs = reader.next())
      loaded.push_back(loadGrayImage(dynamic_cast<mrpt::obs::CObservationImage&>(*obs), reader));
  }
  ASSERT_EQ(loaded.size(), 2u);
  expectSamePixels(loaded[0], img);
  expectSamePixels(loaded[1], mask);

  for (const auto& f : std::filesystem::directory_iterator(dir.file("seq_Images")))
    if (f.path().filename().string().rfind("PLANE_MASK", 0) == 0)
      std::filesystem::resize_file(f.path(), std::filesystem::file_size(f.path()) - 5);
  RawlogReader reader(path);
  loadGrayImage(dynamic_cast<mrpt::obs::CObservationImage&>(*reader.next()), reader);
  try {
    loadGrayImage(dynamic_cast<mrpt::obs::CObservationImage&>(*reader.next()), reader);
    FAIL() << "a truncated mask was decoded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ":entry 2"), std::string::npos) << what;
    EXPECT_NE(what.find("PLANE_MASK_"), std::string::npos) << what;
    EXPECT_NE(what.find("truncated"), std::string::npos) << what;
  }
}

}  // namespace rpvio
