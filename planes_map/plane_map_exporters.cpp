#include "planes_map/plane_map_exporters.h"

#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <octomap/OcTree.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/input_file.h"
#include "common/sensor_types.h"
#include "common/text_table.h"

namespace rpvio {
namespace {

template <typename Seq>
void writeList(std::ostream& out, const Seq& values) {
  out << "[";
  bool first = true;
  for (const auto& v : values) {
    out << (first ? "" : ", ") << v;
    first = false;
  }
  out << "]";
}

/// Numbers of a flow list "[a, b, [c, d]]" (brackets and commas ignored).
std::vector<double> numbersIn(const std::string& text, const std::string& path, int line) {
  std::string cleaned = text;
  for (char& c : cleaned)
    if (c == '[' || c == ']' || c == ',') c = ' ';
  std::istringstream ss(cleaned);
  std::vector<double> out;
  for (std::string token; ss >> token;) out.push_back(parseFiniteNumber(token, path, line));
  return out;
}

/// `x` as an Int of at least `lowest`, or InputError naming the key (a cast of a number out of
/// the type's range is undefined).
template <typename Int>
Int wholeNumber(double x, Int lowest, const std::string& key, const std::string& path, int line) {
  // max() + 1 is a power of two, exact as a double.
  if (!(x == std::floor(x) && x >= lowest &&
        x < static_cast<double>(std::numeric_limits<Int>::max()) + 1))
    throw InputError(path, "line " + std::to_string(line),
                     "'" + key + "' needs whole numbers from " + std::to_string(lowest) + " to " +
                         std::to_string(std::numeric_limits<Int>::max()));
  return static_cast<Int>(x);
}

/// The triangles of a polygon fan (first vertex shared).
template <typename Fn>
void forEachFanTriangle(const Plane& p, Fn fn) {
  for (size_t k = 1; k + 1 < p.polygon.size(); ++k)
    fn(p.polygon[0], p.polygon[k], p.polygon[k + 1]);
}

}  // namespace

std::array<uint8_t, 3> planeColour(int id) {
  return {static_cast<uint8_t>((id * 97) % 200 + 55), static_cast<uint8_t>((id * 57) % 200 + 55),
          static_cast<uint8_t>((id * 151) % 200 + 55)};
}

void writePlanesYaml(const std::string& path, const std::vector<Plane>& planes) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out << std::setprecision(10) << "# rpvio plane map (schema: planes_map/plane_map_exporters.h)\n"
        << "planes:\n";
    for (const Plane& p : planes) {
      out << "  - id: " << p.id << "\n    normal: ";
      writeList(out, std::vector<double>{p.normal.x(), p.normal.y(), p.normal.z()});
      out << "\n    d: " << p.distance << "\n    covariance: ";
      writeList(out, std::vector<double>(p.covariance.data(), p.covariance.data() + 16));
      out << "\n    polygon: [";
      for (size_t k = 0; k < p.polygon.size(); ++k) {
        out << (k ? ", " : "");
        writeList(out, std::vector<double>{p.polygon[k].x(), p.polygon[k].y(), p.polygon[k].z()});
      }
      out << "]\n    support_points: " << p.support.size()
          << "\n    observations: " << p.observations
          << "\n    first_seen: " << stampText(p.first_seen)
          << "\n    last_seen: " << stampText(p.last_seen) << "\n    mask_ids: ";
      writeList(out, p.mask_ids);
      out << "\n";
      if (p.discovered()) out << "    source: discovery\n";
      if (!p.moving) continue;
      const OscillatingTranslation& m = p.motion;
      out << "    moving: true\n    motion: oscillating_translation\n    motion_axis: ";
      writeList(out, std::vector<double>{m.axis.x(), m.axis.y(), m.axis.z()});
      out << "\n    motion_amplitude: " << m.amplitude << "\n    motion_period: " << m.period
          << "\n    motion_phase: " << m.phase << "\n";
    }
  });
}

std::vector<Plane> readPlanesYaml(const std::string& path) {
  std::ifstream in = openInputFile(path);
  std::vector<Plane> planes;
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const auto hash = raw.find('#');
    const std::string s = raw.substr(0, hash);
    const auto colon = s.find(':');
    if (colon == std::string::npos) continue;
    std::string key = s.substr(0, colon);
    key.erase(0, key.find_first_not_of(" -"));
    key.erase(key.find_last_not_of(' ') + 1);
    const std::string value = s.substr(colon + 1);
    if (key == "planes") continue;
    if (s.find("- id:") != std::string::npos) planes.emplace_back();
    if (planes.empty())
      throw InputError(path, "line " + std::to_string(line), "entry outside a plane");
    Plane& p = planes.back();
    if (key == "moving" || key == "motion" || key == "source") {
      std::string word = value;
      word.erase(0, word.find_first_not_of(' '));
      word.erase(word.find_last_not_of(' ') + 1);
      const bool known = key == "moving"   ? word == "true" || word == "false"
                         : key == "motion" ? word == "oscillating_translation"
                                           : word == "discovery";  // implied by mask_ids
      if (!known)
        throw InputError(path, "line " + std::to_string(line),
                         "unknown " + key + " '" + word + "'");
      if (key == "moving") p.moving = word == "true";
      continue;
    }
    const auto v = numbersIn(value, path, line);
    auto need = [&](size_t n) {
      if (v.size() != n)
        throw InputError(path, "line " + std::to_string(line),
                         "'" + key + "' needs " + std::to_string(n) + " numbers");
    };
    if (key == "id")
      need(1), p.id = wholeNumber(v[0], std::numeric_limits<int>::min(), key, path, line);
    else if (key == "normal")
      need(3), p.normal = Eigen::Vector3d(v[0], v[1], v[2]);
    else if (key == "d")
      need(1), p.distance = v[0];
    else if (key == "covariance")
      need(16), p.covariance = Eigen::Map<const Eigen::Matrix4d>(v.data());
    else if (key == "polygon") {
      if (v.size() % 3)
        throw InputError(path, "line " + std::to_string(line), "polygon needs xyz triples");
      for (size_t k = 0; k < v.size(); k += 3) p.polygon.emplace_back(v[k], v[k + 1], v[k + 2]);
    } else if (key == "observations")
      need(1), p.observations = wholeNumber(v[0], size_t{0}, key, path, line);
    else if (key == "first_seen")
      need(1), p.first_seen = v[0];
    else if (key == "last_seen")
      need(1), p.last_seen = v[0];
    else if (key == "mask_ids")
      for (double m : v) p.mask_ids.insert(wholeNumber(m, 0, key, path, line));
    else if (key == "motion_axis")
      need(3), p.motion.axis = Eigen::Vector3d(v[0], v[1], v[2]);
    else if (key == "motion_amplitude")
      need(1), p.motion.amplitude = v[0];
    else if (key == "motion_period")
      need(1), p.motion.period = v[0];
    else if (key == "motion_phase")
      need(1), p.motion.phase = v[0];
  }
  return planes;
}

void writePlanesPly(const std::string& path, const std::vector<Plane>& planes) {
  size_t vertices = 0, faces = 0;
  for (const Plane& p : planes)
    if (p.polygon.size() >= 3) vertices += p.polygon.size(), faces += p.polygon.size() - 2;
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat ascii 1.0\ncomment rpvio plane map: convex hulls, fan-triangulated\n"
        << "element vertex " << vertices
        << "\nproperty float x\nproperty float y\nproperty float z\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        << "element face " << faces << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Plane& p : planes) {
      if (p.polygon.size() < 3) continue;
      const auto c = planeColour(p.id);
      for (const auto& v : p.polygon)
        out << v.x() << " " << v.y() << " " << v.z() << " " << int(c[0]) << " " << int(c[1]) << " "
            << int(c[2]) << "\n";
    }
    size_t base = 0;
    for (const Plane& p : planes) {
      if (p.polygon.size() < 3) continue;
      for (size_t k = 1; k + 1 < p.polygon.size(); ++k)
        out << "3 " << base << " " << base + k << " " << base + k + 1 << "\n";
      base += p.polygon.size();
    }
  });
}

void writePlanesOctomap(const std::string& path, const std::vector<Plane>& planes,
                        double resolution) {
  octomap::OcTree tree(resolution);
  for (const Plane& p : planes)
    for (const auto& x : p.support) tree.updateNode(octomap::point3d(x.x(), x.y(), x.z()), true);
  tree.updateInnerOccupancy();
  const std::string tmp = temporaryPathFor(path);
  if (!tree.writeBinary(tmp)) throw std::runtime_error(path + ": cannot write the OctoMap");
  commitTemporary(path);
}

void writePlanesScene(const std::string& path, const std::vector<Plane>& planes) {
  mrpt::opengl::COpenGLScene scene;
  auto triangles = mrpt::opengl::CSetOfTriangles::Create();
  for (const Plane& p : planes) {
    const auto c = planeColour(p.id);
    forEachFanTriangle(p, [&](const auto& a, const auto& b, const auto& d) {
      mrpt::opengl::TTriangle t(mrpt::math::TPoint3Df(a.x(), a.y(), a.z()),
                                mrpt::math::TPoint3Df(b.x(), b.y(), b.z()),
                                mrpt::math::TPoint3Df(d.x(), d.y(), d.z()));
      t.setColor(mrpt::img::TColor(c[0], c[1], c[2]));
      triangles->insertTriangle(t);
    });
  }
  scene.insert(triangles);
  const std::string tmp = temporaryPathFor(path);
  if (!scene.saveToFile(tmp)) throw std::runtime_error(path + ": cannot write the 3D scene");
  commitTemporary(path);
}

void writePlanesTopView(const std::string& png_path, const std::vector<Plane>& planes,
                        const Trajectory& trajectory) {
  double x0 = 1e18, x1 = -1e18, y0 = 1e18, y1 = -1e18;
  auto extend = [&](const Eigen::Vector3d& p) {
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
    y1 = std::max(y1, p.y());
  };
  for (const Plane& p : planes)
    for (const auto& v : p.polygon) extend(v);
  for (const auto& s : trajectory) extend(s.p);
  if (x0 > x1) x0 = y0 = -1, x1 = y1 = 1;
  const int size = 900, margin = 50;
  const double scale = (size - 2 * margin) / std::max({x1 - x0, y1 - y0, 1e-3});
  auto px = [&](const Eigen::Vector3d& p) {
    return cv::Point(margin + static_cast<int>((p.x() - x0) * scale),
                     size - margin - static_cast<int>((p.y() - y0) * scale));
  };
  cv::Mat img(size, size, CV_8UC3, cv::Scalar(255, 255, 255));
  // Bottom up (mean height), so crate tops cover the floor; ceilings (horizontal planes above the
  // camera's mean height, or above the middle of the map's heights without a trajectory) are
  // outlines only, so they hide nothing below them. The normal's sign says nothing: an estimate's
  // n·X = d may face either way.
  auto height = [](const Plane* p) {
    double z = 0;
    for (const auto& v : p->polygon) z += v.z();
    return p->polygon.empty() ? 0.0 : z / p->polygon.size();
  };
  double ceiling_above = 0;
  if (!trajectory.empty()) {
    for (const auto& s : trajectory) ceiling_above += s.p.z() / trajectory.size();
  } else {
    double z0 = 1e18, z1 = -1e18;
    for (const Plane& p : planes)
      for (const auto& v : p.polygon) z0 = std::min(z0, v.z()), z1 = std::max(z1, v.z());
    ceiling_above = z0 <= z1 ? 0.5 * (z0 + z1) : 0.0;
  }
  std::vector<const Plane*> order;
  for (const Plane& p : planes) order.push_back(&p);
  std::stable_sort(order.begin(), order.end(),
                   [&](const Plane* a, const Plane* b) { return height(a) < height(b); });
  for (const Plane* p : order) {
    if (p->polygon.size() < 3) continue;
    std::vector<cv::Point> poly;
    for (const auto& v : p->polygon) poly.push_back(px(v));
    const auto c = planeColour(p->id);
    const bool ceiling = std::abs(p->normal.z()) > 0.9 && height(p) > ceiling_above;
    if (!ceiling) cv::fillConvexPoly(img, poly, cv::Scalar(c[2], c[1], c[0]), cv::LINE_AA);
    cv::polylines(img, poly, true, ceiling ? cv::Scalar(c[2], c[1], c[0]) : cv::Scalar(60, 60, 60),
                  ceiling ? 2 : 1, cv::LINE_AA);
  }
  for (size_t k = 1; k < trajectory.size(); ++k)
    cv::line(img, px(trajectory[k - 1].p), px(trajectory[k].p), cv::Scalar(0, 0, 0), 2,
             cv::LINE_AA);
  // Scale bar of a round number of metres.
  const double bar = std::pow(10.0, std::floor(std::log10((x1 - x0) / 3)));
  cv::line(img, {margin, size - 20}, {margin + static_cast<int>(bar * scale), size - 20},
           cv::Scalar(0, 0, 0), 3);
  char label[64];
  std::snprintf(label, sizeof(label), "%g m  (top view, x right, y up)", bar);
  cv::putText(img, label, {margin, size - 28}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
  const std::string tmp = temporaryPathFor(png_path) + ".png";
  if (!cv::imwrite(tmp, img)) throw std::runtime_error(png_path + ": cannot write");
  std::filesystem::rename(tmp, png_path);
}

}  // namespace rpvio
