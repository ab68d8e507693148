#include "mrpt_modules/initialization/window_structure.h"

#include <cmath>

#include "mrpt_modules/initialization/triangulation.h"

namespace rpvio {
namespace {

Eigen::Vector3d rayOf(const SfmWindow& window, const SfmObservation& o) {
  return (window.cameras[o.frame]->R_r_c * o.u.homogeneous()).normalized();
}

/// Triangulates a track from its observation `here` (in a solved frame) and the solved observation
/// whose ray makes the widest angle with it, if wider than the minimum.
void triangulateFrom(SfmWindow& window, SfmTrack& track, const SfmObservation& here,
                     double min_angle_deg) {
  const Eigen::Vector3d ray = rayOf(window, here);
  const SfmObservation* other = nullptr;
  double best_cos = std::cos(min_angle_deg * M_PI / 180);
  for (const auto& o : track.observations) {
    if (o.frame == here.frame || !window.cameras[o.frame]) continue;
    const double c = ray.dot(rayOf(window, o));
    if (c < best_cos) best_cos = c, other = &o;
  }
  if (other)
    track.X_r = triangulateTwoView(*window.cameras[here.frame], here.u,
                                   *window.cameras[other->frame], other->u);
}

/// Gives a point to every track seen in frame k that has none yet.
void addPoints(SfmWindow& window, size_t k, const WindowStructureOptions& options) {
  for (auto& track : window.tracks) {
    if (track.X_r) continue;
    const SfmObservation* here = nullptr;
    for (const auto& o : track.observations)
      if (o.frame == k) here = &o;
    if (!here) continue;
    const auto plane = window.planes.find(track.plane_id);
    if (plane != window.planes.end())
      track.X_r =
          intersectRayWithPlane(*window.cameras[k], here->u, plane->second.n, plane->second.d);
    else
      triangulateFrom(window, track, *here, options.min_triangulation_angle_deg);
  }
}

/// Locates frame k by PnP from its neighbour's pose: on the points of the known planes when there
/// are enough, else on all points; else its position alone on all points, its rotation the
/// neighbour's turned by the gyroscope's. Points off the planes that disagree with the pose are
/// dropped (triangulated again later from other rays).
bool locate(SfmWindow& window, size_t k, size_t neighbour, const WindowStructureOptions& options) {
  const bool known_rotation_allowed = static_cast<bool>(options.camera_rotation);
  for (const int attempt : {0, 1, 2}) {
    const bool planes_only = attempt == 0, known_rotation = attempt == 2;
    if (known_rotation && !known_rotation_allowed) continue;
    if (planes_only && window.planes.empty()) continue;
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector2d> u;
    std::vector<SfmTrack*> used;
    for (auto& track : window.tracks) {
      if (!track.X_r || (planes_only && !window.planes.count(track.plane_id))) continue;
      for (const auto& o : track.observations)
        if (o.frame == k) points.push_back(*track.X_r), u.push_back(o.u), used.push_back(&track);
    }
    if (planes_only && points.size() < 2 * options.pnp.min_points) continue;
    std::vector<bool> inlier;
    if (known_rotation)
      // X_r = R_r_n X_n and X_n = Rᵀ X_k with R the rotation from the neighbour to k.
      window.cameras[k] = cameraPositionFromKnownRotation(
          points, u,
          window.cameras[neighbour]->R_r_c * options.camera_rotation(neighbour, k).transpose(),
          options.min_known_rotation_points, options.pnp, &inlier);
    else
      window.cameras[k] =
          cameraPoseFromPnp(points, u, window.cameras[neighbour], options.pnp, &inlier);
    if (!window.cameras[k]) continue;
    for (size_t i = 0; i < used.size(); ++i)
      if (!inlier[i] && !window.planes.count(used[i]->plane_id)) used[i]->X_r.reset();
    addPoints(window, k, options);
    return true;
  }
  return false;
}

}  // namespace

bool buildWindowStructure(SfmWindow& window, size_t l, size_t r, const CameraPose& r_in_l,
                          const WindowStructureOptions& options, std::string* why_not) {
  const size_t n = window.cameras.size();
  window.cameras.assign(n, std::nullopt);
  for (auto& track : window.tracks) track.X_r.reset();
  window.cameras[l] = CameraPose{};
  window.cameras[r] = r_in_l;
  addPoints(window, l, options);
  addPoints(window, r, options);
  auto lost = [&](size_t k) {
    if (why_not) *why_not = "structure lost at window frame " + std::to_string(k);
    return false;
  };
  for (size_t k = l + 1; k < n; ++k)
    if (k != r && !locate(window, k, k - 1, options)) return lost(k);
  for (size_t k = l; k-- > 0;)
    if (!locate(window, k, k + 1, options)) return lost(k);
  // Widest pair of rays for the points off the planes: the first and the last observations are
  // the most divergent ones in practice; try every observation as one end.
  for (auto& track : window.tracks) {
    if (window.planes.count(track.plane_id)) continue;
    std::vector<Eigen::Vector3d> rays;
    for (const auto& o : track.observations) rays.push_back(rayOf(window, o));
    const SfmObservation* widest = nullptr;
    double best_cos = 2;
    for (size_t a = 0; a < rays.size(); ++a)
      for (size_t b = a + 1; b < rays.size(); ++b)
        if (rays[a].dot(rays[b]) < best_cos)
          best_cos = rays[a].dot(rays[b]), widest = &track.observations[a];
    if (widest) triangulateFrom(window, track, *widest, options.min_triangulation_angle_deg);
  }
  return true;
}

}  // namespace rpvio
