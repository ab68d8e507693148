#pragma once
// The keyframes' pose graph with yaw and position free and roll and pitch held at the odometry's
// (gravity makes them observable: VINS-Mono's 4-DoF graph, Qin et al., T-RO 2018, §VIII-C). An
// edge (i, j) measures the position of j in i's frame and the yaw from i to j:
//   r_p = R(ψ_i, θ_i, φ_i)ᵀ (p_j − p_i) − p̂_ij,   r_ψ = wrap(ψ_j − ψ_i − ψ̂_ij).
// Sequential edges come from the odometry, loop edges from the revisits' PnP (with a Cauchy loss).
// A loaded map's keyframes come first and are held where the map has them; the run's keyframes
// are moved into the map's frame by their first revisit of it (relocalization), then solved with
// the map's keyframes as the anchor.
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "common/options.h"

namespace rpvio {

struct PoseGraphOptions {
  int loop_sequential_edges = 4;  // each keyframe to this many before it
  double loop_edge_cauchy = 0.5;  // m or rad: the loop edges' Cauchy scale
  double loop_yaw_weight = 10;    // a yaw residual of 0.1 rad weighs as 1 m

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, loop_sequential_edges);
    RPVIO_OPTION(v, loop_edge_cauchy);
    RPVIO_OPTION(v, loop_yaw_weight);
  }
};

/// Yaw, pitch, roll (Z-Y-X) of a rotation.
Eigen::Vector3d yawPitchRoll(const Eigen::Matrix3d& R);
Eigen::Matrix3d fromYawPitchRoll(double yaw, double pitch, double roll);

/// The 4-DoF edge residual above for poses (ψ_i, p_i), (ψ_j, p_j), weighted (r_p, w·r_ψ).
struct FourDofEdgeResidual {
  FourDofEdgeResidual(const Eigen::Vector3d& p_ij, double yaw_ij, double pitch_i, double roll_i,
                      double yaw_weight)
      : p_ij_(p_ij), yaw_ij_(yaw_ij), pitch_i_(pitch_i), roll_i_(roll_i), yaw_weight_(yaw_weight) {}

  template <typename T>
  bool operator()(const T* yaw_i, const T* p_i, const T* yaw_j, const T* p_j, T* r) const;

  Eigen::Vector3d p_ij_;
  double yaw_ij_, pitch_i_, roll_i_, yaw_weight_;
};

class FourDofPoseGraph {
 public:
  explicit FourDofPoseGraph(const PoseGraphOptions& options) : options_(options) {}

  /// A keyframe of a loaded map (before any addKeyframe): held at `body`, in the map's frame.
  size_t addMapKeyframe(const Eigen::Isometry3d& body);
  /// Adds the next keyframe (body in world, as the odometry has it); its index is returned. It is
  /// linked to the run's keyframes before it by the odometry's relative poses.
  size_t addKeyframe(const Eigen::Isometry3d& odometry);
  /// A revisit: keyframe `old`'s body as the PnP places it in `query`'s world. The first revisit
  /// of a map keyframe moves the run's keyframes by the yaw and translation it implies.
  void addLoop(size_t old, size_t query, const Eigen::Isometry3d& old_body);
  /// Solves the graph: the map's keyframes held, or without a revisit of them the run's first.
  void optimize();
  /// The run's keyframes are in the map's frame (a map keyframe was revisited).
  bool relocalized() const { return relocalized_; }
  /// Forgets the run's keyframes, not the map's.
  void clearSession();

  size_t size() const { return nodes_.size(); }
  size_t loops() const { return loops_; }
  /// Keyframe k's body pose after the last optimize() (the odometry's before any).
  Eigen::Isometry3d corrected(size_t k) const;
  /// corrected(k) · odometry(k)⁻¹: what moves the odometry's world onto the graph's at k.
  Eigen::Isometry3d correction(size_t k) const;

 private:
  struct Node {
    Eigen::Isometry3d odometry;
    double pitch, roll;       // held
    double yaw[1];            // free
    std::array<double, 3> p;  // free
  };
  struct Edge {
    size_t i, j;
    Eigen::Vector3d p_ij;
    double yaw_ij;
    bool loop;
  };
  void addEdge(size_t i, size_t j, const Eigen::Isometry3d& T_i, const Eigen::Isometry3d& T_j,
               bool loop);

  PoseGraphOptions options_;
  std::vector<Node> nodes_;
  std::vector<Edge> edges_;
  size_t loops_ = 0;
  size_t map_nodes_ = 0;  // the first ones
  bool relocalized_ = false;
};

template <typename T>
bool FourDofEdgeResidual::operator()(const T* yaw_i, const T* p_i, const T* yaw_j, const T* p_j,
                                     T* r) const {
  using std::cos, std::sin, std::atan2;
  const T cy = cos(yaw_i[0]), sy = sin(yaw_i[0]);
  const double cp = std::cos(pitch_i_), sp = std::sin(pitch_i_);
  const double cr = std::cos(roll_i_), sr = std::sin(roll_i_);
  // R = Rz(ψ) Ry(θ) Rx(φ); r_p = Rᵀ (p_j − p_i) − p̂_ij.
  Eigen::Matrix<T, 3, 3> R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      T(-sp), T(cp * sr), T(cp * cr);
  const Eigen::Matrix<T, 3, 1> d(p_j[0] - p_i[0], p_j[1] - p_i[1], p_j[2] - p_i[2]);
  const Eigen::Matrix<T, 3, 1> rp = R.transpose() * d - p_ij_.cast<T>();
  const T dyaw = yaw_j[0] - yaw_i[0] - T(yaw_ij_);
  r[0] = rp[0];
  r[1] = rp[1];
  r[2] = rp[2];
  r[3] = T(yaw_weight_) * atan2(sin(dyaw), cos(dyaw));
  return true;
}

}  // namespace rpvio
