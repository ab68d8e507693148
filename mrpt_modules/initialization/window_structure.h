#pragma once
// The up-to-scale structure of the whole window from its initial frame pair (VINS-Mono's global
// SfM, with RP-VIO's planes): points of the pair, then every other frame by PnP on the points
// known so far (forward from the pair's first frame, then backward), each new frame adding the
// points it can: features of a known plane by intersecting their ray with the plane, the others by
// two-view triangulation with an earlier solved observation. A frame the PnP cannot place (too few
// points) is placed by its position alone, its rotation the gyroscope's from the frame it is
// located from. Once every frame is located, the points off the known planes are triangulated again
// from their two most divergent rays.
#include <functional>
#include <string>

#include "mrpt_modules/initialization/camera_pnp.h"
#include "mrpt_modules/initialization/sfm_window.h"

namespace rpvio {

struct WindowStructureOptions {
  PnpOptions pnp;
  double min_triangulation_angle_deg = 2.0;  // between the two rays of a triangulated point
  /// The cameras' rotation from frame a to frame b, X_cb = R X_ca (the gyroscope's); unset: a
  /// frame with too few points for a PnP loses the structure.
  std::function<Eigen::Matrix3d(size_t a, size_t b)> camera_rotation;
  size_t min_known_rotation_points = 3;  // for a position alone (two fix it; one more checks)
};

/// `window.cameras[l]` becomes the identity and `window.cameras[r]` = `r_in_l`; the planes already
/// in `window.planes` (reference frame l) are used for their tracks. False (and why) if a frame
/// cannot be located.
bool buildWindowStructure(SfmWindow& window, size_t l, size_t r, const CameraPose& r_in_l,
                          const WindowStructureOptions& options, std::string* why_not = nullptr);

}  // namespace rpvio
