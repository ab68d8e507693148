#include "sim/simulator.h"

#include <cmath>

#include "sim/motion_blur.h"

namespace rpvio::sim {
namespace {
SceneParams seeded(SceneParams p, uint64_t seed) {
  p.seed = seed;
  return p;
}
}  // namespace

Simulator::Simulator(const SimConfig& config)
    : config_(config),
      camera_(config.camera.intrinsics()),
      T_BC_(config.camera.T_BC()),
      flight_(config.flight),
      scene_(seeded(config.scene, config.seed)),
      auto_exposure_(config.auto_exposure, config.camera_rate) {
  if (config.crowd.layout == CrowdLayout::Flight) {
    const double tan_half_fov = 0.5 * camera_.width / camera_.fx;
    scene_.setCharacters(makeFlightCrowd(config.scene.characters, config.crowd, flight_, T_BC_,
                                         tan_half_fov, config.duration, config.seed));
  }
}

Eigen::Isometry3d Simulator::bodyPose(double t) const {
  const FlightState s = flight_.at(t);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = s.R_wb;
  T.translation() = s.p;
  return T;
}

Eigen::Isometry3d Simulator::cameraPose(double t) const { return bodyPose(t) * T_BC_; }

std::vector<double> Simulator::frameTimes() const {
  std::vector<double> times;
  const auto n = static_cast<int>(std::floor(config_.duration * config_.camera_rate + 1e-9));
  for (int k = 0; k <= n; ++k) times.push_back(k / config_.camera_rate);
  return times;
}

void Simulator::poseAt(double t) {
  if (t != posed_time_) scene_.setTime(t);
  posed_time_ = t;
}

double Simulator::exposureGain(double t) {
  if (!config_.auto_exposure.enabled) return 1.0;
  const PinholeCamera meter_camera = meteringCamera(camera_);
  return auto_exposure_.gain(t, [&](double t_meter, double gain) {
    poseAt(t_meter);
    const cv::Mat radiance =
        renderRadiance(scene_, meter_camera, cameraPose(t_meter), config_.render).radiance;
    return meteredBrightness(radiance, meter_camera, config_.render.vignetting, gain);
  });
}

RenderedFrame Simulator::render(double t, int frame_index) {
  const double gain = exposureGain(t);
  poseAt(t);
  const uint64_t frame_seed = config_.seed * 1000003ULL + static_cast<uint64_t>(frame_index);
  const Eigen::Isometry3d T_WC = cameraPose(t);
  SceneRadiance sharp = renderRadiance(scene_, camera_, T_WC, config_.render);
  if (config_.exposure_time > 0) {
    const double t_open = t - 0.5 * config_.exposure_time,
                 t_close = t + 0.5 * config_.exposure_time;
    const ShutterInterval shutter{t_open, t_close, cameraPose(t_open), cameraPose(t_close)};
    sharp.radiance = motionBlur(sharp, scene_, camera_, T_WC, shutter, config_.render.threads);
  }
  RenderedFrame frame{exposeImage(sharp.radiance, camera_, config_.render, gain, frame_seed),
                      sharp.mask, sharp.dynamic};
  if (config_.mask.enabled()) degradeMask(frame.mask, config_.mask, frame_seed ^ 0x5bd1e995ULL);
  return frame;
}

SceneHit Simulator::castPixel(double t, double u, double v) {
  poseAt(t);
  const auto [o, d] = pixelRay(camera_, cameraPose(t), u, v);
  return scene_.cast(o, d, 1.0 / camera_.fx);
}

std::optional<Eigen::Vector2d> Simulator::project(double t, const Eigen::Vector3d& X) const {
  const Eigen::Vector3d Xc = cameraPose(t).inverse() * X;
  if (Xc.z() <= 1e-6) return std::nullopt;
  const PinholeCamera& c = camera_;
  return Eigen::Vector2d(c.fx * Xc.x() / Xc.z() + c.cx, c.fy * Xc.y() / Xc.z() + c.cy);
}

double Simulator::dynamicFraction(double t, int stride) {
  poseAt(t);
  const PinholeCamera& c = camera_;
  const Eigen::Isometry3d T_WC = cameraPose(t);
  const WarehouseScene::PlanesInView view = scene_.planesInView(T_WC.translation());
  int seen = 0, total = 0;
  for (int v = stride / 2; v < c.height; v += stride)
    for (int u = stride / 2; u < c.width; u += stride, ++total)
      seen += scene_.cast(view, pixelRay(c, T_WC, u, v).second, 1.0 / c.fx).dynamic;
  return static_cast<double>(seen) / std::max(1, total);
}

double Simulator::distanceToCharacters(double t, const Eigen::Vector3d& X) {
  poseAt(t);
  return scene_.distanceToCharacters(X);
}

std::vector<ImuSample> Simulator::imuStream(std::vector<ImuBiasState>* true_biases) const {
  return simulateImu(flight_, config_.imu, config_.initial_bias, config_.duration,
                     config_.imu_noise, config_.seed * 7777 + 1, true_biases);
}

}  // namespace rpvio::sim
