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

void Plane::supportFromPolygon(double spacing) {
  support = polygon;
  if (polygon.size() < 3) return;
  Eigen::Vector3d origin, u, v;
  planeFrame(origin, u, v);
  std::vector<cv::Point2f> flat;
  for (const auto& p : polygon)
    flat.emplace_back(static_cast<float>((p - origin).dot(u)),
                      static_cast<float>((p - origin).dot(v)));
  const cv::Rect2f box = cv::boundingRect(flat);
  for (double a = box.x; a <= box.x + box.width; a += spacing)
    for (double b = box.y; b <= box.y + box.height; b += spacing)
      if (cv::pointPolygonTest(flat, cv::Point2f(static_cast<float>(a), static_cast<float>(b)),
                               false) >= 0)
        support.push_back(origin + a * u + b * v);
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

Plane Plane::transformed(const Eigen::Isometry3d& T) const {
  Plane moved = *this;
  const Eigen::Matrix3d R = T.linear();
  moved.normal = R * normal;
  moved.distance = distance + moved.normal.dot(T.translation());
  Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
  J.topLeftCorner<3, 3>() = R;
  J.bottomLeftCorner<1, 3>() = T.translation().transpose() * R;
  J(3, 3) = 1;
  moved.covariance = J * covariance * J.transpose();
  for (Eigen::Vector3d& x : moved.support) x = T * x;
  for (Eigen::Vector3d& x : moved.polygon) x = T * x;
  moved.motion.axis = R * motion.axis;
  return moved;
}

}  // namespace rpvio
