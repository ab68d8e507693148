#include "planes_map/plane.h"

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <tuple>

namespace rpvio {

void Plane::planeFrame(Eigen::Vector3d& origin, Eigen::Vector3d& u, Eigen::Vector3d& v) const {
  origin = distance * normal;
  const Eigen::Vector3d helper =
      std::abs(normal.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  u = helper.cross(normal).normalized();
  v = normal.cross(u);
}

void Plane::updatePolygon() {
  polygon.clear();
  if (support.size() < 3) return;
  Eigen::Vector3d origin, u, v;
  planeFrame(origin, u, v);
  std::vector<cv::Point2f> flat, hull;
  for (const auto& p : support)
    flat.emplace_back(static_cast<float>((p - origin).dot(u)),
                      static_cast<float>((p - origin).dot(v)));
  cv::convexHull(flat, hull);
  for (const auto& h : hull) polygon.push_back(origin + h.x * u + h.y * v);
}

void Plane::decimateSupport(double voxel, size_t max_points) {
  std::map<std::tuple<long, long, long>, Eigen::Vector3d> cells;
  for (const auto& p : support) {
    const auto key = std::make_tuple(std::lround(std::floor(p.x() / voxel)),
                                     std::lround(std::floor(p.y() / voxel)),
                                     std::lround(std::floor(p.z() / voxel)));
    cells.emplace(key, p);  // first point of each cell is kept: deterministic
  }
  support.clear();
  for (const auto& [key, p] : cells) {
    if (support.size() >= max_points) break;
    support.push_back(p);
  }
}

}  // namespace rpvio
