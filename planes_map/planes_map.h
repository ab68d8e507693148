#pragma once
// The persistent planes map (DESIGN.md §1 step 4): planes outlive the sliding window; a plane seen
// again after leaving it gets its old id and parameters back instead of a new entry.
#include <map>
#include <string>
#include <vector>

#include "common/options.h"
#include "planes_map/plane.h"

namespace rpvio {

struct PlanesMapOptions {
  double max_normal_angle_deg = 8.0;  // association: normals closer than this ...
  double max_distance_m = 0.25;       // ... its points (centroid) closer than this to the plane ...
  double max_gap_m = 1.0;             // ... and supports closer than this (no far-apart twins)
  // Seen again under the mask label it was last seen as: the label is evidence of its own, the
  // geometry only has to be plausible (a far wall's offset drifts by decimetres between windows).
  double max_label_normal_angle_deg = 20.0;
  double max_label_distance_m = 1.0;
  double voxel_size_m = 0.10;  // support decimation
  size_t max_support_points = 3000;
  // A plane is confirmed (exported) once this many optimizations have seen it; before, it may be
  // one window's bad estimate of a known surface (a far wall with few points).
  size_t min_observations = 3;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, max_normal_angle_deg);
    RPVIO_OPTION(v, max_distance_m);
    RPVIO_OPTION(v, max_gap_m);
    RPVIO_OPTION(v, max_label_normal_angle_deg);
    RPVIO_OPTION(v, max_label_distance_m);
    RPVIO_OPTION(v, voxel_size_m);
    RPVIO_OPTION(v, max_support_points);
    RPVIO_OPTION(v, min_observations);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(min_observations >= 1, "min_observations", "must be 1 or more");
  }
  /// Reads the keys present in `section`; InputError (file, line) on a bad value.
  static PlanesMapOptions load(const IniFile& ini, const std::string& section) {
    return loadOptions<PlanesMapOptions>(ini, section);
  }
  std::string describe() const { return describeOptions(*this); }
};

/// What the estimator knows of a plane after an optimization.
struct PlaneObservation {
  int mask_id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double distance = 0;
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity() * 1e-2;
  std::vector<Eigen::Vector3d> points;  // world points of its features
  double time = 0;
  // Estimates of one visit (the plane's stay in the estimator's window, which keeps what it
  // learnt of the plane) replace each other: the newest knows all the earlier ones did. Different
  // visits are fused. 0: every observation is independent.
  uint64_t visit = 0;
};

class PlanesMap {
 public:
  explicit PlanesMap(const PlanesMapOptions& options = {}) : options_(options) {}

  /// Associates the observation with an existing plane (the one its mask id currently maps to, or
  /// any compatible one) and fuses it, or creates a new plane. Returns the map id.
  int update(const PlaneObservation& observation);
  /// A plane of another map (a saved one, already in this map's frame): fused into a compatible
  /// plane by its geometry alone (its labels are another run's) or kept as a new entry, with its
  /// counts, times and labels; `associate` false: always a new entry. Returns the map id.
  int addPlane(const Plane& plane, bool associate = true);
  /// Merges planes that have become the same surface; returns how many were merged away.
  size_t mergeDuplicates();

  /// Replaces a plane's (n, d) (the batch refinement's); its covariance stays the windows'.
  void setParameters(int id, const Eigen::Vector3d& normal, double distance);

  const Plane* plane(int id) const;
  /// The confirmed plane a mask label currently stands for (what the estimator may start a visit
  /// from), or nullptr.
  const Plane* planeOfMask(int mask_id) const;
  const std::vector<Plane>& planes() const { return planes_; }
  /// The planes seen in at least min_observations optimizations: the map the exporters write.
  std::vector<Plane> confirmedPlanes() const;
  const PlanesMapOptions& options() const { return options_; }

 private:
  bool isConfirmed(const Plane& plane) const {
    return plane.observations >= options_.min_observations;
  }
  /// Same orientation and offset (the label thresholds when `same_label`); and, unless
  /// `same_label`, supports no farther apart than max_gap_m.
  bool compatible(const Plane& plane, const Eigen::Vector3d& n, double d,
                  const std::vector<Eigen::Vector3d>& points, bool same_label = false) const;
  /// Fuses the observation's (n, d) into the plane's and records it (record()).
  void fuse(Plane& plane, const PlaneObservation& observation) const;
  /// Support points, extent, counts, times and mask label of an observation.
  void record(Plane& plane, const PlaneObservation& observation) const;

  /// A plane's (n, d) and covariance before the visit under way.
  struct VisitStart {
    uint64_t visit = 0;
    bool known = false;  // false: the plane was new in this visit
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double distance = 0;
    Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();
  };

  PlanesMapOptions options_;
  std::map<int, VisitStart> visit_start_;  // by plane id
  std::vector<Plane> planes_;
  std::map<int, int> mask_to_plane_;
  int next_id_ = 1;
};

}  // namespace rpvio
