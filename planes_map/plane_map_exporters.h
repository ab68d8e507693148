#pragma once
// Files a person can open, written at the end of a run (each via a temporary name + rename):
//
// planes.yaml — schema:
//   planes:
//     - id: 3                        # stable map id
//       normal: [nx, ny, nz]         # unit, world frame
//       d: 4.2                       # n·X = d (m)
//       covariance: [16 numbers]     # row-major 4x4 of (n, d): the estimator's windows, fused
//                                    # (none along n itself: the unit constraint)
//       polygon: [[x, y, z], ...]    # convex hull of the support, on the plane (m, world)
//       support_points: 512          # decimated supporting points
//       observations: 40             # updates fused into it
//       first_seen: 1.25             # s
//       last_seen: 79.9              # s
//       mask_ids: [4, 17]            # labels it was seen as (above 255: discovered planes)
//       source: discovery            # only on planes found by the plane discovery (rpvio-auto)
//       moving: true                 # only on moving planes (ground truth of moving objects):
//       motion: oscillating_translation  # then plane and polygon are at t = 0 and every point
//       motion_axis: [ax, ay, az]    #   moves by A (sin(2π t / T + φ) − sin φ) along the unit axis
//       motion_amplitude: 3.5        # A (m)
//       motion_period: 14.7          # T (s)
//       motion_phase: 0.5            # φ (rad)
// planes.ply — ASCII PLY, each polygon triangulated as a fan, vertices coloured by plane id.
// planes.bt — OctoMap (liboctomap binary) of the supporting points at `resolution` m.
// planes.3Dscene — MRPT scene (SceneViewer3D): the polygons as coloured triangles.
// planes_topview.png — polygons seen from above, coloured by id, with an optional trajectory.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/sensor_types.h"
#include "planes_map/plane.h"

namespace rpvio {

void writePlanesYaml(const std::string& path, const std::vector<Plane>& planes);
/// Reads what writePlanesYaml wrote (id, normal, d, covariance, polygon, counts, times, mask ids,
/// motion; not the support points). InputError (file, line) on malformed content.
std::vector<Plane> readPlanesYaml(const std::string& path);
void writePlanesPly(const std::string& path, const std::vector<Plane>& planes);
void writePlanesOctomap(const std::string& path, const std::vector<Plane>& planes,
                        double resolution);
void writePlanesScene(const std::string& path, const std::vector<Plane>& planes);
void writePlanesTopView(const std::string& png_path, const std::vector<Plane>& planes,
                        const Trajectory& trajectory = {});

/// A colour per plane id (RGB, 0..255), shared by every exporter.
std::array<uint8_t, 3> planeColour(int id);

}  // namespace rpvio
