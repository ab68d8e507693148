#include "mrpt_modules/loop/keyframe_map_file.h"

#include <libdeflate.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "common/atomic_file.h"
#include "common/input_error.h"

namespace rpvio {
namespace {

constexpr char kMagic[8] = {'R', 'P', 'V', 'I', 'O', 'M', 'A', 'P'};
constexpr uint32_t kVersion = 1;
constexpr int kDescriptorBytes = 32;
// Per point: normalized x, y (doubles) and the descriptor.
constexpr size_t kPointBytes = 2 * sizeof(double) + kDescriptorBytes;

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void putBytes(const void* data, size_t n) {
    const auto* p = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), p, p + n);
  }
  void putPose(const Eigen::Isometry3d& T) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) put(T.matrix()(r, c));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  ByteReader(const std::string& path, const std::string& bytes, size_t end)
      : path_(path), bytes_(bytes), end_(end) {}
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(path_, "byte " + std::to_string(at_), why);
  }
  size_t left() const { return end_ - at_; }
  template <typename T>
  T get(const char* what) {
    T value;
    getBytes(&value, sizeof(T), what);
    return value;
  }
  void getBytes(void* out, size_t n, const char* what) {
    if (n > left()) fail(std::string("truncated: ") + what + " runs past the end");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  double getFinite(const char* what) {
    const size_t at = at_;
    const double v = get<double>(what);
    if (!std::isfinite(v)) {
      at_ = at;
      fail(std::string("not a finite number: ") + what);
    }
    return v;
  }
  Eigen::Isometry3d getPose(const char* what) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const size_t at = at_;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) T.matrix()(r, c) = getFinite(what);
    const Eigen::Matrix3d R = T.linear();
    if (!(R.transpose() * R).isIdentity(1e-6) || R.determinant() < 0) {
      at_ = at;
      fail(std::string("not a rotation: ") + what);
    }
    return T;
  }

 private:
  const std::string& path_;
  const std::string& bytes_;
  const size_t end_;
  size_t at_ = 0;
};

uint32_t crc32Of(const std::string& bytes, size_t n) {
  return libdeflate_crc32(0, bytes.data(), n);
}

bool near(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); }

}  // namespace

std::string keyframeMapPath(const std::string& dir) {
  return (std::filesystem::path(dir) / "keyframes.rpvmap").string();
}

std::string mapPlanesPath(const std::string& dir) {
  return (std::filesystem::path(dir) / "planes.yaml").string();
}

void writeKeyframeMap(const std::string& path, const KeyframeMap& map) {
  ByteWriter w;
  w.putBytes(kMagic, sizeof kMagic);
  w.put(kVersion);
  w.put<int32_t>(map.camera.width);
  w.put<int32_t>(map.camera.height);
  w.put<int32_t>(static_cast<int32_t>(map.camera.model));
  for (double v : {map.camera.fx, map.camera.fy, map.camera.cx, map.camera.cy}) w.put(v);
  for (double v : map.camera.distortion) w.put(v);
  w.putPose(map.T_BC);
  w.put<uint64_t>(map.keyframes.size());
  for (const StoredKeyframe& k : map.keyframes) {
    const KeyframeAppearance& a = k.appearance;
    if (a.descriptors.rows != static_cast<int>(a.points.size()) ||
        (a.descriptors.rows > 0 &&
         (a.descriptors.cols != kDescriptorBytes || a.descriptors.type() != CV_8U)))
      throw std::logic_error("writeKeyframeMap: one 32-byte descriptor per point expected");
    w.put(k.t);
    w.putPose(k.body);
    w.put<uint64_t>(a.points.size());
    for (const AppearancePoint& p : a.points) w.put(p.normalized.x()), w.put(p.normalized.y());
    for (int r = 0; r < a.descriptors.rows; ++r) w.putBytes(a.descriptors.ptr(r), kDescriptorBytes);
  }
  w.put<uint32_t>(crc32Of(w.bytes(), w.bytes().size()));
  writeFileAtomically(path, [&](std::ostream& s) { s << w.bytes(); });
}

KeyframeMap readKeyframeMap(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file)
    throw InputError(path, "", "cannot open the map (--map DIR: a folder --save-map wrote)");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (bytes.size() < sizeof kMagic + sizeof(uint32_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(path, "byte 0", "not an rpvio keyframe map (no RPVIOMAP header)");
  const size_t body_end = bytes.size() - sizeof(uint32_t);
  uint32_t stored_crc;
  std::memcpy(&stored_crc, bytes.data() + body_end, sizeof stored_crc);
  if (crc32Of(bytes, body_end) != stored_crc)
    throw InputError(path, "byte " + std::to_string(body_end),
                     "CRC mismatch: the file is damaged or truncated");
  ByteReader r(path, bytes, body_end);
  char magic[sizeof kMagic];
  r.getBytes(magic, sizeof magic, "the header");
  const auto version = r.get<uint32_t>("the version");
  if (version != kVersion)
    r.fail("version " + std::to_string(version) + ", this program reads version " +
           std::to_string(kVersion));
  KeyframeMap map;
  map.camera.width = r.get<int32_t>("the image width");
  map.camera.height = r.get<int32_t>("the image height");
  const auto model = r.get<int32_t>("the distortion model");
  if (model < static_cast<int32_t>(DistortionModel::None) ||
      model > static_cast<int32_t>(DistortionModel::Equidistant))
    r.fail("unknown distortion model " + std::to_string(model));
  map.camera.model = static_cast<DistortionModel>(model);
  for (double* v : {&map.camera.fx, &map.camera.fy, &map.camera.cx, &map.camera.cy})
    *v = r.getFinite("an intrinsic");
  for (double& v : map.camera.distortion) v = r.getFinite("a distortion coefficient");
  map.T_BC = r.getPose("the camera-body pose");
  const auto count = r.get<uint64_t>("the keyframe count");
  // A keyframe takes at least its time, pose and point count.
  if (count > r.left() / (13 * sizeof(double) + sizeof(uint64_t)))
    r.fail(std::to_string(count) + " keyframes cannot fit in the bytes left");
  map.keyframes.resize(count);
  for (StoredKeyframe& k : map.keyframes) {
    k.t = r.getFinite("a keyframe's time");
    k.body = r.getPose("a keyframe's pose");
    const auto points = r.get<uint64_t>("a point count");
    if (points > r.left() / kPointBytes)
      r.fail(std::to_string(points) + " points cannot fit in the bytes left");
    k.appearance.points.resize(points);
    for (AppearancePoint& p : k.appearance.points)
      p.normalized = {r.getFinite("a point"), r.getFinite("a point")};
    k.appearance.descriptors.create(static_cast<int>(points), kDescriptorBytes, CV_8U);
    for (int row = 0; row < static_cast<int>(points); ++row)
      r.getBytes(k.appearance.descriptors.ptr(row), kDescriptorBytes, "a descriptor");
  }
  if (r.left() != 0) r.fail(std::to_string(r.left()) + " bytes after the last keyframe");
  return map;
}

std::string calibrationMismatch(const KeyframeMap& map, const Calibration& calibration) {
  const CameraIntrinsics& a = map.camera;
  const CameraIntrinsics& b = calibration.camera;
  if (a.width != b.width || a.height != b.height)
    return "the map's images are " + std::to_string(a.width) + "x" + std::to_string(a.height) +
           ", the calibration's " + std::to_string(b.width) + "x" + std::to_string(b.height);
  if (a.model != b.model) return "the map's distortion model differs from the calibration's";
  bool same = near(a.fx, b.fx) && near(a.fy, b.fy) && near(a.cx, b.cx) && near(a.cy, b.cy);
  for (size_t i = 0; i < a.distortion.size(); ++i)
    same = same && near(a.distortion[i], b.distortion[i]);
  if (!same) return "the map's intrinsics or distortion differ from the calibration's";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      if (!near(map.T_BC.matrix()(r, c), calibration.T_BC.matrix()(r, c)))
        return "the map's camera-body pose (T_BC) differs from the calibration's";
  return "";
}

}  // namespace rpvio
