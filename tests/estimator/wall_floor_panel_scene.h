#pragma once
// The scene of the plane verification and discovery tests: a camera turning and moving sideways
// past a wall and a floor (static) and a panel in front of the wall (which a test may move).
#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

namespace rpvio::test {

constexpr int kWall = 1, kFloor = 2, kPanel = 3;

struct ScenePoint {
  int id, plane;
  Eigen::Vector3d at_t0;
};

struct WallFloorPanel {
  double yaw_rate = 0.4;  // rad/s, about the camera's y axis
  double panel_z = 4.5;   // m; the wall is at 6 m, the floor 1.5 m below the camera
  double panel_step_x = 0.25, panel_step_y = 0.3;  // spacing of the panel's points (m)

  /// World from camera: yaw about the camera's y axis (y points down).
  Eigen::Matrix3d cameraRotation(double t) const {
    return Eigen::AngleAxisd(yaw_rate * t, Eigen::Vector3d::UnitY()).toRotationMatrix();
  }
  Eigen::Vector3d cameraPosition(double t) const { return {t, 0, 0.3 * t}; }  // 1 m/s sideways

  std::vector<ScenePoint> points() const {
    std::vector<ScenePoint> points;
    int id = 0;
    for (double x = -3; x <= 4; x += 0.5)
      for (double y = -1.5; y <= 1.0; y += 0.5) points.push_back({id++, kWall, {x, y, 6}});
    for (double x = -2; x <= 3; x += 0.5)
      for (double z = 2; z <= 5; z += 0.5) points.push_back({id++, kFloor, {x, 1.5, z}});
    for (double x = 0.6; x <= 1.6; x += panel_step_x)
      for (double y = -0.8; y <= 0.4; y += panel_step_y)
        points.push_back({id++, kPanel, {x, y, panel_z}});
    return points;
  }

  /// The normalized image point of X at time t, if in front and within the field of view.
  std::optional<Eigen::Vector2d> project(double t, const Eigen::Vector3d& X) const {
    const Eigen::Vector3d X_c = cameraRotation(t).transpose() * (X - cameraPosition(t));
    if (X_c.z() < 0.5 || std::abs(X_c.x() / X_c.z()) > 0.8 || std::abs(X_c.y() / X_c.z()) > 0.6)
      return std::nullopt;
    return X_c.hnormalized();
  }
};

}  // namespace rpvio::test
