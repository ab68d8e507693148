#include "rawlog_io/calibration.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "rawlog_io/atomic_file.h"
#include "rawlog_io/input_error.h"

namespace rpvio {
namespace {

// Minimal INI reader keeping line numbers, so errors can name them.
struct IniValue {
  std::string text;
  int line = 0;
};
using IniSections = std::map<std::string, std::map<std::string, IniValue>>;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

IniSections parseIni(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open calibration file");
  IniSections sections;
  std::string section, raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string s = trim(raw.substr(0, raw.find_first_of(";#")));
    if (s.empty()) continue;
    if (s.front() == '[') {
      if (s.back() != ']') throw InputError(path, "line " + std::to_string(line), "bad section");
      section = trim(s.substr(1, s.size() - 2));
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string::npos || section.empty())
      throw InputError(path, "line " + std::to_string(line), "expected 'key = value' in a section");
    sections[section][trim(s.substr(0, eq))] = {trim(s.substr(eq + 1)), line};
  }
  return sections;
}

class IniLookup {
 public:
  IniLookup(std::string path, IniSections sections)
      : path_(std::move(path)), sections_(std::move(sections)) {}

  bool has(const std::string& section, const std::string& key) const {
    auto s = sections_.find(section);
    return s != sections_.end() && s->second.count(key);
  }

  std::vector<double> numbers(const std::string& section, const std::string& key,
                              size_t count) const {
    if (!has(section, key))
      throw InputError(path_, "[" + section + "]", "missing key '" + key + "'");
    const IniValue& v = sections_.at(section).at(key);
    std::istringstream ss(v.text);
    std::vector<double> out;
    std::string token;
    while (ss >> token) {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (*end != '\0' || !std::isfinite(x))
        throw InputError(path_, "line " + std::to_string(v.line),
                         "'" + key + "': not a finite number: " + token);
      out.push_back(x);
    }
    if (out.size() != count)
      throw InputError(path_, "line " + std::to_string(v.line),
                       "'" + key + "' needs " + std::to_string(count) + " number(s)");
    return out;
  }
  double number(const std::string& section, const std::string& key) const {
    return numbers(section, key, 1)[0];
  }
  double numberOr(const std::string& section, const std::string& key, double fallback) const {
    return has(section, key) ? number(section, key) : fallback;
  }
  std::string text(const std::string& section, const std::string& key) const {
    if (!has(section, key))
      throw InputError(path_, "[" + section + "]", "missing key '" + key + "'");
    return sections_.at(section).at(key).text;
  }
  int line(const std::string& section, const std::string& key) const {
    return sections_.at(section).at(key).line;
  }

 private:
  std::string path_;
  IniSections sections_;
};

const char* modelName(DistortionModel m) {
  switch (m) {
    case DistortionModel::RadTan:
      return "radtan";
    case DistortionModel::Equidistant:
      return "equidistant";
    default:
      return "none";
  }
}

}  // namespace

Calibration Calibration::load(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path, "", "calibration file not found");
  const IniLookup ini(path, parseIni(path));
  Calibration c;
  c.camera.width = static_cast<int>(ini.number("camera", "width"));
  c.camera.height = static_cast<int>(ini.number("camera", "height"));
  c.camera.fx = ini.number("camera", "fx");
  c.camera.fy = ini.number("camera", "fy");
  c.camera.cx = ini.number("camera", "cx");
  c.camera.cy = ini.number("camera", "cy");
  if (c.camera.width <= 0 || c.camera.height <= 0 || c.camera.fx <= 0 || c.camera.fy <= 0)
    throw InputError(path, "[camera]", "image size and focal lengths must be positive");
  const std::string model = ini.text("camera", "distortion_model");
  if (model == "radtan") {
    c.camera.model = DistortionModel::RadTan;
  } else if (model == "equidistant") {
    c.camera.model = DistortionModel::Equidistant;
  } else if (model != "none") {
    throw InputError(path, "line " + std::to_string(ini.line("camera", "distortion_model")),
                     "distortion_model must be none, radtan or equidistant");
  }
  if (c.camera.model != DistortionModel::None) {
    const auto d = ini.numbers("camera", "distortion", 4);
    std::copy(d.begin(), d.end(), c.camera.distortion.begin());
  }
  const auto t = ini.numbers("T_BC", "translation", 3);
  const auto q = ini.numbers("T_BC", "rotation", 4);
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (std::abs(rotation.norm() - 1.0) > 1e-6)
    throw InputError(path, "line " + std::to_string(ini.line("T_BC", "rotation")),
                     "T_BC rotation is not a unit quaternion");
  c.T_BC = Eigen::Isometry3d::Identity();
  c.T_BC.linear() = rotation.normalized().toRotationMatrix();
  c.T_BC.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  c.time_offset = ini.numberOr("time", "offset", 0.0);
  c.imu.gyro_noise_density = ini.number("imu", "gyro_noise_density");
  c.imu.accel_noise_density = ini.number("imu", "accel_noise_density");
  c.imu.gyro_random_walk = ini.number("imu", "gyro_random_walk");
  c.imu.accel_random_walk = ini.number("imu", "accel_random_walk");
  c.imu.rate_hz = ini.number("imu", "rate_hz");
  c.imu.gravity = ini.number("imu", "gravity");
  return c;
}

void Calibration::save(const std::string& path) const {
  writeFileAtomically(path, [this](std::ostream& out) {
    out << std::setprecision(17);
    out << "# rpvio calibration (see rawlog_io/calibration.h for the meaning of every key)\n";
    out << "[camera]\nwidth = " << camera.width << "\nheight = " << camera.height
        << "\nfx = " << camera.fx << "\nfy = " << camera.fy << "\ncx = " << camera.cx
        << "\ncy = " << camera.cy << "\ndistortion_model = " << modelName(camera.model) << "\n";
    if (camera.model != DistortionModel::None)
      out << "distortion = " << camera.distortion[0] << " " << camera.distortion[1] << " "
          << camera.distortion[2] << " " << camera.distortion[3] << "\n";
    const Eigen::Quaterniond q(T_BC.linear());
    const Eigen::Vector3d& p = T_BC.translation();
    out << "\n[T_BC]\ntranslation = " << p.x() << " " << p.y() << " " << p.z()
        << "\nrotation = " << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
    out << "\n[time]\noffset = " << time_offset << "\n";
    out << "\n[imu]\ngyro_noise_density = " << imu.gyro_noise_density
        << "\naccel_noise_density = " << imu.accel_noise_density
        << "\ngyro_random_walk = " << imu.gyro_random_walk
        << "\naccel_random_walk = " << imu.accel_random_walk << "\nrate_hz = " << imu.rate_hz
        << "\ngravity = " << imu.gravity << "\n";
  });
}

}  // namespace rpvio
