#include "mrpt_modules/initialization/initializer.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mrpt_modules/initialization/essential_two_view.h"
#include "mrpt_modules/initialization/ground_plane_scale.h"
#include "mrpt_modules/initialization/plane_from_metric_motion.h"
#include "mrpt_modules/initialization/plane_motion_from_homography.h"
#include "mrpt_modules/initialization/visual_bundle_adjustment.h"
#include "mrpt_modules/initialization/visual_inertial_alignment.h"
#include "mrpt_modules/initialization/window_structure.h"

namespace rpvio {
namespace {

using Frames = std::vector<FeatureFrame>;
using Preintegrations = std::vector<std::shared_ptr<ImuPreintegration>>;

InitializationResult failure(InitStatus status, const std::string& detail) {
  InitializationResult r;
  r.status = status;
  const std::string prefix = std::string(toString(status)) + ": ";
  r.reason = detail.rfind(prefix, 0) == 0 ? detail  // already says it
                                          : prefix.substr(0, prefix.size() - 2) +
                                                (detail.empty() ? "" : " (" + detail + ")");
  return r;
}

std::string format(double value, int decimals = 1) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

/// Normalized points of the features common to frames a and b, on `plane` (any when < 0).
void commonPoints(const FeatureFrame& a, const FeatureFrame& b, int plane,
                  std::vector<Eigen::Vector2d>& u_a, std::vector<Eigen::Vector2d>& u_b) {
  std::unordered_map<int, Eigen::Vector2d> in_a;
  for (const auto& f : a.features)
    if (plane < 0 || f.plane_id == plane) in_a[f.id] = f.normalized;
  for (const auto& f : b.features) {
    const auto it = in_a.find(f.id);
    if (it != in_a.end() && (plane < 0 || f.plane_id == plane)) {
      u_a.push_back(it->second);
      u_b.push_back(f.normalized);
    }
  }
}

/// The plane with the most features common to frames a and b, and that count.
std::pair<int, size_t> largestCommonPlane(const FeatureFrame& a, const FeatureFrame& b) {
  std::unordered_map<int, int> plane_in_a;
  for (const auto& f : a.features) plane_in_a[f.id] = f.plane_id;
  std::map<int, size_t> count;
  for (const auto& f : b.features) {
    const auto it = plane_in_a.find(f.id);
    if (f.plane_id > 0 && it != plane_in_a.end() && it->second == f.plane_id) ++count[f.plane_id];
  }
  std::pair<int, size_t> best{-1, 0};
  for (const auto& [plane, c] : count)
    if (c > best.second) best = {plane, c};
  return best;
}

/// Camera rotation X_cb = R X_ca predicted by the (bias-uncorrected) gyroscope from frame a to b.
Eigen::Matrix3d gyroCameraRotation(const Preintegrations& imu, size_t a, size_t b,
                                   const Eigen::Matrix3d& R_BC) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (size_t k = a + 1; k <= b; ++k) q = q * imu[k]->deltaQ();
  return cameraRotationFromBody(q.toRotationMatrix(), R_BC);
}

/// Mean displacement (px at `focal`) once the rotation R is compensated; the raw displacement when
/// smaller (a still camera with a biased gyroscope must not look like it translates).
double translationalParallax(const std::vector<Eigen::Vector2d>& a,
                             const std::vector<Eigen::Vector2d>& b, const Eigen::Matrix3d& R,
                             double focal) {
  double compensated = 0, raw = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    compensated += (b[k] - (R * a[k].homogeneous()).hnormalized()).norm();
    raw += (b[k] - a[k]).norm();
  }
  return a.empty() ? 0 : focal * std::min(compensated, raw) / a.size();
}

double angleDeg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(A.transpose() * B).angle() * 180 / M_PI;
}

CameraPose inverse(const CameraPose& c) {
  return {c.R_r_c.transpose(), -c.R_r_c.transpose() * c.p_r_c};
}
CameraPose compose(const CameraPose& a, const CameraPose& b) {
  return {a.R_r_c * b.R_r_c, a.R_r_c * b.p_r_c + a.p_r_c};
}

}  // namespace

const char* toString(InitStatus status) {
  switch (status) {
    case InitStatus::kSuccess:
      return "initialized";
    case InitStatus::kCollectingFrames:
      return "collecting frames";
    case InitStatus::kTooFewPlaneFeatures:
      return "too few plane features";
    case InitStatus::kTooFewFeatures:
      return "too few features";
    case InitStatus::kTooLittleParallax:
      return "too little parallax";
    case InitStatus::kTooLittleImuExcitation:
      return "too little IMU excitation";
    case InitStatus::kGeometryFailed:
      return "two-view geometry failed";
    case InitStatus::kAlignmentRejected:
      return "alignment rejected";
  }
  return "unknown";
}

Initializer::Initializer(const Calibration& calibration, const InitializerOptions& options)
    : mrpt::system::COutputLogger("Initializer"), calibration_(calibration), options_(options) {}

InitializationResult Initializer::tryInitialize(const Frames& frames, const Preintegrations& imu,
                                                const std::optional<KnownStart>& start) {
  InitializationResult result = attempt(frames, imu, start);
  if (result.status != last_status_) {
    MRPT_LOG_INFO_STREAM("t=" << timeText(frames.empty() ? 0.0 : frames.back().t) << ": "
                              << result.reason);
    last_status_ = result.status;
  }
  return result;
}

InitializationResult Initializer::attempt(const Frames& all_frames, const Preintegrations& imu,
                                          const std::optional<KnownStart>& start) const {
  const InitializerOptions& o = options_;
  const size_t n = all_frames.size();
  if (n < std::max<size_t>(o.min_frames, 4) || imu.size() != n)
    return failure(InitStatus::kCollectingFrames, std::to_string(n) + " frames");
  if (all_frames.back().t - all_frames.front().t < o.min_window_s - 1e-6)
    return failure(InitStatus::kCollectingFrames,
                   format(all_frames.back().t - all_frames.front().t, 2) + " s of window");
  for (size_t k = 1; k < n; ++k)
    if (!imu[k])
      return failure(InitStatus::kCollectingFrames, "no IMU before frame " + std::to_string(k));
  const bool planar = o.method == InitializerMethod::kPlanarHomography;
  // Planar modes only use features on static planes.
  Frames frames = all_frames;
  if (planar)
    for (auto& f : frames)
      f.features.erase(std::remove_if(f.features.begin(), f.features.end(),
                                      [](const TrackedFeature& x) { return x.plane_id <= 0; }),
                       f.features.end());
  const Eigen::Matrix3d R_BC = calibration_.T_BC.linear();

  // Candidate pairs (i, j): enough common features (of one plane in planar mode) and parallax.
  struct Pair {
    size_t i, j;
    int plane;
    double parallax;
    std::vector<Eigen::Vector2d> u_i, u_j;
  };
  std::vector<Pair> pairs;
  size_t most_features = 0;
  double most_parallax = -1;  // over the pairs with enough features
  for (size_t j = n; j-- > 1;)
    for (size_t i = 0; i < j; ++i) {
      Pair p{i, j, planar ? largestCommonPlane(frames[i], frames[j]).first : -1, 0, {}, {}};
      commonPoints(frames[i], frames[j], p.plane, p.u_i, p.u_j);
      most_features = std::max(most_features, p.u_i.size());
      if (p.u_i.size() < (planar ? o.min_plane_features : o.min_features)) continue;
      p.parallax =
          translationalParallax(p.u_i, p.u_j, gyroCameraRotation(imu, i, j, R_BC), o.virtual_focal);
      most_parallax = std::max(most_parallax, p.parallax);
      if (p.parallax >= std::min(o.min_parallax_px, o.fallback_parallax_px))
        pairs.push_back(std::move(p));
    }
  // Pairs below min_parallax_px only when no pair reaches it.
  if (most_parallax >= o.min_parallax_px)
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const Pair& p) { return p.parallax < o.min_parallax_px; }),
                pairs.end());
  if (pairs.empty()) {
    if (most_parallax < 0)
      return failure(planar ? InitStatus::kTooFewPlaneFeatures : InitStatus::kTooFewFeatures,
                     "at most " + std::to_string(most_features) + " common to two frames");
    return failure(InitStatus::kTooLittleParallax, format(most_parallax) + " px");
  }
  // The best-conditioned pairs first: the two-view geometry's precision grows with the parallax
  // and with the square root of the number of correspondences. (Ordering by features alone picks
  // the pair with the least baseline above min_parallax_px.) A few are tried until one agrees
  // with the gyroscope.
  auto conditioning = [](const Pair& p) {
    return p.parallax * std::sqrt(static_cast<double>(p.u_i.size()));
  };
  std::sort(pairs.begin(), pairs.end(),
            [&](const Pair& a, const Pair& b) { return conditioning(a) > conditioning(b); });
  const size_t kMaxAttempts = 5;
  std::string why, geometry_failure;
  SfmWindow window = SfmWindow::fromFrames(frames);
  const Pair* chosen = nullptr;
  CameraPose j_in_i;  // in SfM units: plane distance 1 (planar) or unit baseline (essential)
  for (size_t a = 0; a < std::min(kMaxAttempts, pairs.size()) && !chosen; ++a) {
    const Pair& p = pairs[a];
    const Eigen::Matrix3d R_gyro = gyroCameraRotation(imu, p.i, p.j, R_BC);
    if (planar) {
      HomographyInitOptions h;
      h.ransac_threshold_px = o.homography_ransac_px;
      h.virtual_focal = o.virtual_focal;
      h.min_inliers = o.min_plane_features;
      const auto motion = planeMotionFromHomography(p.u_i, p.u_j, R_gyro, h, &why);
      if (!motion) {
        geometry_failure = why;
        continue;
      }
      if (motion->rotation_error_deg > o.max_gyro_disagreement_deg) {
        geometry_failure = "homography rotation " + format(motion->rotation_error_deg) +
                           " deg from the gyroscope's";
        continue;
      }
      j_in_i = inverse(CameraPose{motion->R, motion->t_over_d});
      window.planes[p.plane] = SfmPlane{motion->n, 1.0};
    } else {
      EssentialOptions e;
      e.ransac_threshold_px = o.essential_ransac_px;
      e.virtual_focal = o.virtual_focal;
      const auto pose = relativePoseFromEssential(p.u_i, p.u_j, e, &why);
      if (!pose) {
        geometry_failure = why;
        continue;
      }
      const double disagreement = angleDeg(pose->i_j.R_r_c.transpose(), R_gyro);
      if (disagreement > o.max_gyro_disagreement_deg) {
        geometry_failure =
            "essential rotation " + format(disagreement) + " deg from the gyroscope's";
        continue;
      }
      j_in_i = pose->i_j;
    }
    chosen = &p;
  }
  if (!chosen) return failure(InitStatus::kGeometryFailed, geometry_failure);
  const size_t l = chosen->i, r = chosen->j;
  const int plane = chosen->plane;
  // Structure of the whole window, bundle adjustment (gauge: camera l and the scale unit).
  WindowStructureOptions structure;
  structure.camera_rotation = [&](size_t a, size_t b) {
    return a < b ? gyroCameraRotation(imu, a, b, R_BC)
                 : Eigen::Matrix3d(gyroCameraRotation(imu, b, a, R_BC).transpose());
  };
  if (!buildWindowStructure(window, l, r, j_in_i, structure, &why))
    return failure(InitStatus::kGeometryFailed, why);
  BundleAdjustmentGauge gauge;
  gauge.fixed_frame = l;
  if (planar)
    gauge.fixed_distance_plane = plane;
  else
    gauge.fixed_position_frame = r;
  BundleAdjustmentOptions ba;
  ba.sqrt_info = o.virtual_focal / o.pixel_sigma;
  const BundleAdjustmentReport adjusted = bundleAdjust(window, gauge, ba);
  if (adjusted.final_rms_px > o.max_ba_rms_px)
    return failure(InitStatus::kGeometryFailed,
                   "bundle adjustment RMS " + format(adjusted.final_rms_px, 2) + " px");

  // Alignment in the frame of camera 0, on copies of the preintegrations.
  const CameraPose c0_l = inverse(*window.cameras[0]);
  std::vector<UpToScaleFrame> up_to_scale(n);
  InitializationResult result;
  for (size_t k = 0; k < n; ++k) {
    const CameraPose c0_k = compose(c0_l, *window.cameras[k]);
    up_to_scale[k].R_c0_c = c0_k.R_r_c;
    up_to_scale[k].p_c0_c = c0_k.p_r_c;
    if (k > 0) up_to_scale[k].from_previous = std::make_shared<ImuPreintegration>(*imu[k]);
    result.imu.push_back(up_to_scale[k].from_previous);
  }
  // With the camera's height above a flat ground known (calib.ini [ground] camera_height), a
  // labelled plane of the window that is that ground gives the metric scale, whether or not the
  // IMU's accelerations make it observable (ground_plane_scale.h); the alignment's gravity must
  // then agree that the plane is level.
  std::optional<AlignmentResult> aligned;
  std::optional<GroundPlane> ground;
  if (planar && calibration_.camera_height > 0) {
    std::vector<Eigen::Matrix3d> R_l_b;
    for (size_t k = 0; k < n; ++k) R_l_b.push_back(window.cameras[k]->R_r_c * R_BC.transpose());
    ground = findGroundPlane(window, gravityDirection(R_l_b, imu), o.max_ground_tilt_deg,
                             o.min_plane_features);
    if (ground)
      aligned = alignVisualInertial(up_to_scale, calibration_.T_BC, calibration_.imu.gravity, &why,
                                    calibration_.camera_height / ground->d);
    if (aligned) {
      const double cosine = (c0_l.R_r_c * ground->n_r).dot(aligned->gravity_c0.normalized());
      if (std::acos(std::clamp(cosine, -1.0, 1.0)) > o.max_ground_tilt_deg * M_PI / 180)
        aligned.reset();
    }
    if (!aligned) ground.reset();
  }
  if (!aligned) {
    // A known start: its body velocity in camera 0, v_c0 = (R_w_b R_BC)ᵀ v_w.
    std::optional<Eigen::Vector3d> v_c0;
    if (start) v_c0 = (start->R_w_b * R_BC).transpose() * start->v_w;
    aligned = alignVisualInertial(up_to_scale, calibration_.T_BC, calibration_.imu.gravity, &why,
                                  {}, v_c0);
    if (!aligned) return failure(InitStatus::kAlignmentRejected, why);
    if (aligned->scale_sigma > o.max_relative_scale_sigma * aligned->scale)
      return failure(
          InitStatus::kTooLittleImuExcitation,
          "scale uncertain by " + format(100 * aligned->scale_sigma / aligned->scale) + "%");
  }

  // World: gravity along −z, origin at body 0, yaw of body 0 zero.
  const double s = aligned->scale;
  const Eigen::Matrix3d R_c0_b0 = up_to_scale[0].R_c0_c * R_BC.transpose();
  const Eigen::Matrix3d tilt =
      Eigen::Quaterniond::FromTwoVectors(aligned->gravity_c0, -Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  const Eigen::Matrix3d tilted_b0 = tilt * R_c0_b0;
  const double yaw = std::atan2(tilted_b0(1, 0), tilted_b0(0, 0));
  const Eigen::Matrix3d R_w_c0 =
      Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
  const Eigen::Vector3d t_BC = calibration_.T_BC.translation();
  const Eigen::Vector3d p_c0_b0 = -R_c0_b0 * t_BC;  // metric
  auto toWorld = [&](const Eigen::Vector3d& metric_c0) { return R_w_c0 * (metric_c0 - p_c0_b0); };
  result.ba = frames.size() > 1 ? Eigen::Vector3d(imu[1]->linearizedBa() + aligned->accel_bias)
                                : Eigen::Vector3d::Zero();
  result.bg = aligned->gyro_bias;
  for (size_t k = 0; k < n; ++k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R_w_c0 * up_to_scale[k].R_c0_c * R_BC.transpose();
    T.translation() = toWorld(s * up_to_scale[k].p_c0_c) - T.linear() * t_BC;
    result.T_w_b.push_back(T);
    result.v_w.push_back(R_w_c0 * aligned->velocity_c0[k]);
    if (result.imu[k]) result.imu[k]->repropagate(result.ba, result.bg);
  }
  auto addPlane = [&](int id, const Eigen::Vector3d& n_l, double metric_d_l) {
    const Eigen::Vector3d n_c0 = c0_l.R_r_c * n_l;
    const double d_c0 = metric_d_l + n_c0.dot(s * c0_l.p_r_c);
    result.planes[id] = WorldPlane{R_w_c0 * n_c0, d_c0 - n_c0.dot(p_c0_b0)};
  };
  if (planar) {
    result.reference_plane = plane;
    addPlane(plane, window.planes[plane].n, s * window.planes[plane].d);
    // Other planes: their own decomposition between l and r against the metric motion.
    const CameraPose r_in_l = *window.cameras[r];
    const Eigen::Matrix3d R = r_in_l.R_r_c.transpose();
    const Eigen::Vector3d t = -R * (s * r_in_l.p_r_c);
    std::map<int, size_t> seen;
    for (const auto& f : frames[r].features) ++seen[f.plane_id];
    for (const auto& [other, count] : seen) {
      if (other == plane || count < o.min_plane_features) continue;
      std::vector<Eigen::Vector2d> a, b;
      commonPoints(frames[l], frames[r], other, a, b);
      HomographyInitOptions h;
      h.ransac_threshold_px = o.homography_ransac_px;
      h.virtual_focal = o.virtual_focal;
      h.min_inliers = o.min_plane_features;
      if (const auto p = planeFromMetricMotion(a, b, R, t, h)) addPlane(other, p->n, p->d);
    }
  }
  for (const auto& track : window.tracks) {
    if (!track.X_r) continue;
    const size_t f = track.observations.front().frame;
    const double depth = window.cameras[f]->toCamera(*track.X_r).z() * s;
    if (depth > 0) result.depths[track.feature_id] = FeatureDepth{f, depth};
  }
  result.pair_first = l;
  result.pair_last = r;
  result.scale = s;
  result.status = InitStatus::kSuccess;
  result.reason =
      std::string(toString(InitStatus::kSuccess)) + " (pair " + std::to_string(l) + "-" +
      std::to_string(r) + ", scale " + format(s, 3) + ", BA RMS " +
      format(adjusted.final_rms_px, 2) + " px, ba " + format(result.ba.norm(), 3) + ", bg " +
      format(result.bg.norm(), 4) +
      (ground ? ", scale from the camera height over plane " + std::to_string(ground->plane_id)
              : std::string()) +
      ")";
  result.scale_from_camera_height = ground.has_value();
  return result;
}

}  // namespace rpvio
