#pragma once
// Sensor labels of the rawlog conventions (DESIGN.md §4).
namespace rpvio::labels {
constexpr const char* kCamera = "CAM0";
constexpr const char* kPlaneMask = "PLANE_MASK";
constexpr const char* kImu = "IMU";
constexpr const char* kGroundTruth = "GROUND_TRUTH";
}  // namespace rpvio::labels
