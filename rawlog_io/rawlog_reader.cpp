#include "rawlog_io/rawlog_reader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/lazy_load_path.h>
#include <mrpt/serialization/CArchive.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/input_error.h"
#include "common/input_file.h"
#include "rawlog_io/mrpt_conversions.h"
#include "rawlog_io/png_gray_decoder.h"

namespace fs = std::filesystem;

namespace rpvio {

double toSeconds(const mrpt::Clock::time_point& t) { return mrpt::Clock::toDouble(t); }
mrpt::Clock::time_point fromSeconds(double t) { return mrpt::Clock::fromDouble(t); }

namespace {

/// Counts the bytes handed out, so a clean end of file (no byte of a new entry) can be told from a
/// file that ends inside an entry.
class CountingStream : public mrpt::io::CStream {
 public:
  explicit CountingStream(mrpt::io::CStream& inner) : inner_(inner) {}
  size_t Read(void* buffer, size_t count) override {
    const size_t n = inner_.Read(buffer, count);
    bytes_ += n;
    return n;
  }
  size_t Write(const void*, size_t) override { return 0; }
  uint64_t Seek(int64_t, mrpt::io::CStream::TSeekOrigin) override { return bytes_; }
  uint64_t getTotalBytesCount() const override { return inner_.getTotalBytesCount(); }
  uint64_t getPosition() const override { return bytes_; }

 private:
  mrpt::io::CStream& inner_;
  uint64_t bytes_ = 0;
};

}  // namespace

struct RawlogReader::Impl {
  std::string path, images_dir;
  mrpt::io::CFileGZInputStream gz;
  CountingStream stream{gz};
  size_t entries = 0;
  mrpt::Clock::time_point last_stamp{};
  bool has_last = false;

  std::string entry() const { return "entry " + std::to_string(entries + 1); }
};

RawlogReader::RawlogReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  requireRegularFile(path, "rawlog file");
  if (!impl_->gz.open(path)) throw InputError(path, "", "cannot open rawlog");
  // MRPT 2.5.8's CRawlog::detectImagesDirectory() fails for paths with a directory part.
  const fs::path p = fs::absolute(path);
  impl_->images_dir = (p.parent_path() / (p.stem().string() + "_Images")).string();
  mrpt::io::setLazyLoadPathBase(impl_->images_dir);
}

RawlogReader::~RawlogReader() = default;

mrpt::obs::CObservation::Ptr RawlogReader::next() {
  Impl& d = *impl_;
  const uint64_t position_before = d.stream.getPosition();
  mrpt::serialization::CSerializable::Ptr object;
  try {
    auto archive = mrpt::serialization::archiveFrom(d.stream);
    object = archive.ReadObject();
  } catch (const mrpt::serialization::CExceptionEOF&) {
    if (d.stream.getPosition() == position_before) return nullptr;  // clean end of file
    throw InputError(d.path, d.entry(), "truncated rawlog (file ends inside an entry)");
  } catch (const std::exception&) {
    throw InputError(d.path, d.entry(),
                     d.entries == 0 ? "not an MRPT rawlog" : "corrupt or truncated entry");
  }
  auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object);
  if (!obs)
    throw InputError(d.path, d.entry(),
                     "not an observation (only observation-only rawlogs are supported)");
  if (d.has_last && obs->timestamp < d.last_stamp)
    throw InputError(d.path, d.entry(),
                     "timestamp goes backwards (" + std::to_string(toSeconds(obs->timestamp)) +
                         " s after " + std::to_string(toSeconds(d.last_stamp)) + " s)");
  d.last_stamp = obs->timestamp;
  d.has_last = true;
  ++d.entries;
  return obs;
}

size_t RawlogReader::entriesRead() const { return impl_->entries; }
const std::string& RawlogReader::path() const { return impl_->path; }
const std::string& RawlogReader::imagesDir() const { return impl_->images_dir; }

namespace {

/// The image in `file`: 8-bit grayscale PNGs by PngGrayDecoder, anything else by OpenCV. Its
/// buffers are kept per thread, between frames.
cv::Mat decodeImageFile(const std::string& file, const std::string& rawlog,
                        const std::string& entry) {
  thread_local PngGrayDecoder decoder;
  thread_local std::vector<uint8_t> bytes;
  std::error_code error;
  const auto size = fs::file_size(file, error);  // an error for a missing file or a folder
  std::ifstream in(file, std::ios::binary);
  if (error || size == 0 || !in)
    throw InputError(rawlog, entry, "image missing or unreadable: " + file);
  bytes.resize(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw InputError(rawlog, entry, "image unreadable: " + file);
  cv::Mat img;
  std::string why;
  switch (decoder.decode(bytes.data(), bytes.size(), img, why)) {
    case PngGrayDecoder::Status::Decoded:
      return img;
    case PngGrayDecoder::Status::Corrupt:
      throw InputError(rawlog, entry, "image unreadable: " + file + " (" + why + ")");
    case PngGrayDecoder::Status::OtherVariant:
      break;
  }
  img = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (img.empty()) throw InputError(rawlog, entry, "image missing or unreadable: " + file);
  return img;
}

}  // namespace

ImageFileRef locateImage(const mrpt::obs::CObservationImage& obs, const RawlogReader& reader) {
  ImageFileRef ref{"", reader.path(), "entry " + std::to_string(reader.entriesRead())};
  if (!obs.image.isExternallyStored())
    throw InputError(ref.rawlog, ref.entry, "image is not stored externally (DESIGN.md §4)");
  ref.file = obs.image.getExternalStorageFile();
  if (fs::path(ref.file).is_relative())
    ref.file = (fs::path(reader.imagesDir()) / ref.file).string();
  return ref;
}

cv::Mat decodeGrayImage(const ImageFileRef& ref) {
  cv::Mat img = decodeImageFile(ref.file, ref.rawlog, ref.entry);
  if (img.channels() == 3) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  if (img.type() != CV_8UC1)
    throw InputError(ref.rawlog, ref.entry, "image is not 8-bit grayscale: " + ref.file);
  return img;
}

cv::Mat loadGrayImage(const mrpt::obs::CObservationImage& obs, const RawlogReader& reader) {
  return decodeGrayImage(locateImage(obs, reader));
}

ImuSample toImuSample(const mrpt::obs::CObservationIMU& obs, const RawlogReader& reader) {
  using namespace mrpt::obs;
  const TIMUDataIndex fields[6] = {IMU_WX, IMU_WY, IMU_WZ, IMU_X_ACC, IMU_Y_ACC, IMU_Z_ACC};
  double v[6];
  for (int i = 0; i < 6; ++i) {
    // MRPT reads the presence flags as raw bytes: in a corrupt file they may be neither 0 nor 1,
    // and loading such a byte as a bool (has(), get()) is undefined behaviour.
    unsigned char present = 0;
    std::memcpy(&present, &obs.dataIsPresent[fields[i]], 1);
    v[i] = obs.rawMeasurements[fields[i]];
    if (present != 1 || !std::isfinite(v[i]))
      throw InputError(reader.path(), "entry " + std::to_string(reader.entriesRead()),
                       "IMU sample missing or not finite");
  }
  ImuSample s;
  s.t = toSeconds(obs.timestamp);
  s.gyro = {v[0], v[1], v[2]};
  s.accel = {v[3], v[4], v[5]};
  return s;
}

StampedPose toStampedPose(const mrpt::obs::CObservationRobotPose& obs) {
  const Eigen::Isometry3d T = toIsometry(obs.pose.mean);
  StampedPose p;
  p.t = toSeconds(obs.timestamp);
  p.p = T.translation();
  p.q = Eigen::Quaterniond(T.linear());
  return p;
}

}  // namespace rpvio
