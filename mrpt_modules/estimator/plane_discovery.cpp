#include "mrpt_modules/estimator/plane_discovery.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>

namespace rpvio {
namespace {

// Labels of ended tracks are kept this long (s): longer than an initialization window.
constexpr double kLabelMemoryS = 5;

/// Drops the entries last seen before `t`.
template <class Map>
void forgetOlderThan(Map& entries, double t) {
  for (auto it = entries.begin(); it != entries.end();)
    it = it->second.last_seen_t < t ? entries.erase(it) : std::next(it);
}

/// Normalized-plane transfer error of a pair under y ~ x + t (mᵀ x).
double transferError(const BearingPair& p, const Eigen::Vector3d& t, const Eigen::Vector3d& m) {
  const Eigen::Vector3d mapped = p.rotated_j + t * m.dot(p.rotated_j);
  if (mapped.z() <= 1e-9) return INFINITY;
  return (mapped.hnormalized() - p.k.hnormalized()).norm();
}

/// The camera's translation direction by MSAC over two-point hypotheses, and its inliers.
std::optional<Eigen::Vector3d> translationConsensus(const std::vector<BearingPair>& pairs,
                                                    double limit, int iterations,
                                                    std::mt19937& random) {
  std::vector<Eigen::Vector3d> constraints;  // x × y, unit; t is orthogonal to all static ones
  std::vector<size_t> usable;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector3d c = pairs[i].rotated_j.cross(pairs[i].k);
    constraints.push_back(c.norm() > 1e-12 ? Eigen::Vector3d(c.normalized()) : c);
    if (c.norm() > 1e-12) usable.push_back(i);
  }
  if (usable.size() < 2) return std::nullopt;
  std::uniform_int_distribution<size_t> pick(0, usable.size() - 1);
  const auto cost = [&](const Eigen::Vector3d& t) {
    double sum = 0;
    for (const BearingPair& p : pairs)
      sum += std::min(std::pow(epipolarDistance(p, t), 2), limit * limit);
    return sum;
  };
  double best_cost = INFINITY;
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  for (int it = 0; it < iterations; ++it) {
    const size_t a = usable[pick(random)], b = usable[pick(random)];
    const Eigen::Vector3d t = constraints[a].cross(constraints[b]);
    if (t.norm() < 1e-6) continue;
    const double c = cost(t.normalized());
    if (c < best_cost) {
      best_cost = c;
      best = t.normalized();
    }
  }
  if (best_cost == INFINITY) return std::nullopt;
  std::vector<BearingPair> inliers;
  for (const BearingPair& p : pairs)
    if (epipolarDistance(p, best) < limit) inliers.push_back(p);
  if (inliers.size() < 2) return std::nullopt;
  const Eigen::Vector3d refined = translationDirection(inliers);
  return cost(refined) <= best_cost ? refined : best;
}

/// Signed distance of y from the epipolar line of t through x (normalized image plane).
double signedEpipolarDistance(const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                              const Eigen::Vector3d& t) {
  const Eigen::Vector3d line = t.cross(x);
  const double norm = line.head<2>().norm();
  return norm > 1e-12 ? line.dot(y / y.z()) / norm : 0;
}

/// The gyroscope's rotation corrected by a small rotation δ and the translation direction, by
/// Gauss–Newton on the epipolar distances of the static pairs (numeric Jacobian over δ and the
/// two directions orthogonal to t): an uncorrected gyroscope bias of 0.005 rad/s turns 0.3 s
/// apart frames by 0.7 px, as much as the thresholds. Returns Exp(δ); updates t.
Eigen::Matrix3d refineRotation(const std::vector<BearingPair>& pairs,
                               const std::vector<size_t>& inliers, Eigen::Vector3d& t) {
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  if (inliers.size() < 8) return correction;
  const auto residuals = [&](const Eigen::Matrix3d& R, const Eigen::Vector3d& dir) {
    Eigen::VectorXd r(inliers.size());
    for (size_t i = 0; i < inliers.size(); ++i)
      r(i) = signedEpipolarDistance(R * pairs[inliers[i]].rotated_j, pairs[inliers[i]].k, dir);
    return r;
  };
  const auto step = [&](const Eigen::Matrix<double, 5, 1>& d, Eigen::Matrix3d& R,
                        Eigen::Vector3d& dir) {
    Eigen::Vector3d u = dir.unitOrthogonal(), v = dir.cross(u);
    R = Eigen::AngleAxisd(d.head<3>().norm(), d.head<3>().norm() > 0
                                                  ? Eigen::Vector3d(d.head<3>().normalized())
                                                  : Eigen::Vector3d::UnitX())
            .toRotationMatrix() *
        R;
    dir = (dir + d(3) * u + d(4) * v).normalized();
  };
  for (int iteration = 0; iteration < 5; ++iteration) {
    const Eigen::VectorXd r0 = residuals(correction, t);
    Eigen::MatrixXd J(r0.size(), 5);
    const double h = 1e-6;
    for (int c = 0; c < 5; ++c) {
      Eigen::Matrix<double, 5, 1> d = Eigen::Matrix<double, 5, 1>::Zero();
      d(c) = h;
      Eigen::Matrix3d R = correction;
      Eigen::Vector3d dir = t;
      step(d, R, dir);
      J.col(c) = (residuals(R, dir) - r0) / h;
    }
    const Eigen::Matrix<double, 5, 1> delta = (J.transpose() * J).ldlt().solve(-J.transpose() * r0);
    if (!delta.allFinite()) break;
    Eigen::Matrix3d R = correction;
    Eigen::Vector3d dir = t;
    step(delta, R, dir);
    if (residuals(R, dir).squaredNorm() >= r0.squaredNorm()) break;
    correction = R;
    t = dir;
  }
  return correction;
}

/// t or −t: the one that puts the points in front, their inverse depths ρ = mᵀx, from
/// (y × t) ρ = −(y × x), mostly positive.
Eigen::Vector3d towardsScene(const std::vector<BearingPair>& pairs,
                             const std::vector<size_t>& static_pairs, const Eigen::Vector3d& t) {
  std::vector<double> inverse_depths;
  for (size_t i : static_pairs) {
    const Eigen::Vector3d y = pairs[i].k, yt = y.cross(t);
    if (yt.squaredNorm() > 1e-18)
      inverse_depths.push_back(-yt.dot(y.cross(pairs[i].rotated_j)) / yt.squaredNorm());
  }
  return inverse_depths.empty() || median(inverse_depths) >= 0 ? t : Eigen::Vector3d(-t);
}

/// The transfer error within which a feature lies on a plane: plane_px, or plane_sigmas σ of the
/// static features' epipolar distances when smaller (σ of a zero-mean normal from its median
/// absolute deviation: median / Φ⁻¹(3/4)).
double planeLimit(const PlaneDiscoveryOptions& options,
                  const std::vector<double>& epipolar_distances) {
  constexpr double kMedianAbsoluteDeviationPerSigma = 0.6745;
  const double limit = options.plane_px / options.focal_px;
  if (options.plane_sigmas <= 0 || epipolar_distances.empty()) return limit;
  return std::min(
      limit, options.plane_sigmas * median(epipolar_distances) / kMedianAbsoluteDeviationPerSigma);
}

}  // namespace

/// Least-squares m of (y × t)(xᵀ m) = −(y × x) over the pairs (three rows each).
std::optional<Eigen::Vector3d> planeThroughPairs(const std::vector<BearingPair>& pairs,
                                                 const std::vector<size_t>& members,
                                                 const Eigen::Vector3d& t) {
  Eigen::MatrixX3d A(3 * members.size(), 3);
  Eigen::VectorXd b(3 * members.size());
  for (size_t r = 0; r < members.size(); ++r) {
    const BearingPair& p = pairs[members[r]];
    const Eigen::Vector3d y = p.k / p.k.z();
    A.middleRows<3>(3 * r) = y.cross(t) * p.rotated_j.transpose();
    b.segment<3>(3 * r) = -y.cross(p.rotated_j);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX3d> qr(A);
  if (qr.rank() < 3) return std::nullopt;
  return qr.solve(b);
}

PlaneDiscovery::CheckResult PlaneDiscovery::check(const FeatureFrame& j, const FeatureFrame& k,
                                                  const Eigen::Matrix3d& R_kj) const {
  CheckResult result;
  std::vector<int> ids;
  std::vector<BearingPair> pairs = bearingPairs(j, k, R_kj, &ids);
  result.compared = ids;
  if (pairs.size() < options_.min_features) return result;
  // Rotation-compensated parallax, or the raw image motion when smaller: a still camera with a
  // biased gyroscope (EuRoC's: 0.08 rad/s, 11 px in 0.3 s) must not look like it translates.
  std::vector<double> raw_flow;
  for (const BearingPair& p : pairs)
    raw_flow.push_back(((R_kj.transpose() * p.rotated_j).hnormalized() - p.k.hnormalized()).norm());
  const double raw_parallax = median(raw_flow);
  const auto enough_parallax = [&] {
    std::vector<double> flow;
    for (const BearingPair& p : pairs) flow.push_back(parallax(p));
    return std::min(median(flow), raw_parallax) * options_.focal_px >= options_.min_parallax_px;
  };
  if (!enough_parallax()) return result;

  std::mt19937 random(1);  // the same samples for the same frames: runs repeat exactly
  const double epipolar_limit = options_.epipolar_px / options_.focal_px;
  auto t = translationConsensus(pairs, epipolar_limit, options_.iterations, random);
  if (!t) return result;
  {
    std::vector<size_t> consensus;
    for (size_t i = 0; i < pairs.size(); ++i)
      if (epipolarDistance(pairs[i], *t) < epipolar_limit) consensus.push_back(i);
    const Eigen::Matrix3d correction = refineRotation(pairs, consensus, *t);
    for (BearingPair& p : pairs) p.rotated_j = correction * p.rotated_j;
  }
  if (!enough_parallax()) return result;  // the gyroscope's error was the parallax
  std::vector<size_t> still;              // static, not yet on a plane
  std::vector<double> still_distances;    // their epipolar distances
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double distance = epipolarDistance(pairs[i], *t);
    if (distance < epipolar_limit) {
      still.push_back(i);
      still_distances.push_back(distance);
    } else {
      result.moving.push_back(ids[i]);
    }
  }
  if (2 * still.size() <= pairs.size()) return result;  // no consensus: nothing judged
  result.t = towardsScene(pairs, still, *t);
  result.judged = true;
  const double plane_limit = planeLimit(options_, still_distances);
  const auto members = [&](const Eigen::Vector3d& m) {
    std::vector<size_t> in;
    for (size_t i : still)
      if (transferError(pairs[i], result.t, m) < plane_limit) in.push_back(i);
    return in;
  };
  while (static_cast<int>(result.planes.size()) < options_.max_planes &&
         still.size() >= options_.min_features) {
    std::uniform_int_distribution<size_t> pick(0, still.size() - 1);
    std::vector<size_t> best;
    std::vector<std::vector<size_t>> nearest(pairs.size());  // per seed, among `still`, on demand
    for (int it = 0; it < options_.iterations; ++it) {
      // A feature and two of its nearest image neighbours.
      const size_t seed = still[pick(random)];
      std::vector<size_t>& near = nearest[seed];
      if (near.empty()) {
        std::vector<std::pair<double, size_t>> by_distance;
        for (size_t i : still)
          if (i != seed)
            by_distance.push_back(
                {(pairs[i].k.hnormalized() - pairs[seed].k.hnormalized()).squaredNorm(), i});
        const size_t n = std::min<size_t>(by_distance.size(), options_.sample_neighbours);
        std::partial_sort(by_distance.begin(), by_distance.begin() + n, by_distance.end());
        for (size_t k = 0; k < n; ++k) near.push_back(by_distance[k].second);
      }
      const size_t n = near.size();
      if (n < 2) break;
      std::uniform_int_distribution<size_t> neighbour(0, n - 1);
      const size_t a = neighbour(random);
      size_t b = neighbour(random);
      if (b == a) b = (a + 1) % n;
      const auto m = planeThroughPairs(pairs, {seed, near[a], near[b]}, result.t);
      if (!m) continue;
      std::vector<size_t> in = members(*m);
      if (in.size() > best.size()) best.swap(in);
    }
    if (best.size() < options_.min_features) break;
    // Least squares over the consensus, twice (its members may change once).
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (int round = 0; round < 2; ++round) {
      const auto refined = planeThroughPairs(pairs, best, result.t);
      if (!refined) break;
      m = *refined;
      std::vector<size_t> in = members(m);
      if (in.size() < options_.min_features) break;
      best.swap(in);
    }
    if (best.size() < options_.min_features) break;
    FoundPlane plane{m, {}};
    for (size_t i : best) plane.features.push_back(ids[i]);
    result.planes.push_back(plane);
    std::vector<size_t> rest;
    std::set_difference(still.begin(), still.end(), best.begin(), best.end(),
                        std::back_inserter(rest));
    still.swap(rest);
  }
  return result;
}

void PlaneDiscovery::update(const CheckResult& result, const FeatureFrame& frame) {
  // Every feature a check labelled that is still tracked was compared (it was tracked at the
  // reference frame of that check, which is no newer than this one's); young tracks adopted
  // since (step 4) are not until they reach this check's reference frame. Segments whose
  // compared features mostly moved count a disagreement.
  const std::set<int> moving(result.moving.begin(), result.moving.end());
  const std::set<int> compared(result.compared.begin(), result.compared.end());
  for (const int id : compared) judged_[id] = {!moving.count(id), frame.t};
  std::map<int, std::pair<int, int>> moving_of;  // segment → (moving, compared)
  for (const int id : compared)
    if (const auto it = labels_.find(id); it != labels_.end()) {
      it->second.static_in_last_check = !moving.count(id);
      auto& [moved, seen] = moving_of[it->second.segment];
      moved += moving.count(id) ? 1 : 0;
      ++seen;
    }
  for (const auto& [segment, counts] : moving_of) {
    Segment& s = segments_[segment];
    const auto [moved, compared] = counts;
    if (s.rejected || 2 * compared < static_cast<int>(options_.min_features)) continue;
    s.moving_streak = 2 * moved > compared ? s.moving_streak + 1 : 0;
    if (s.moving_streak < options_.reject_after) continue;
    s.rejected = true;
    if (s.confirmed) events_.push_back({frame.t, segment, false});
  }
  // Match each found plane to the segment most of its labelled features carry.
  std::set<int> matched;
  for (const FoundPlane& plane : result.planes) {
    std::map<int, int> votes;
    for (const int id : plane.features)
      if (const auto it = labels_.find(id);
          it != labels_.end() && !segments_[it->second.segment].rejected)
        ++votes[it->second.segment];
    int segment = 0, most = 0;
    for (const auto& [s, n] : votes)
      if (n > most && !matched.count(s)) {
        segment = s;
        most = n;
      }
    if (3 * most < static_cast<int>(plane.features.size())) segment = next_id_++;
    matched.insert(segment);
    Segment& s = segments_[segment];
    if (++s.found >= options_.confirm_after && !s.confirmed) {
      s.confirmed = true;
      events_.push_back({frame.t, segment, true});
    }
    for (const int id : plane.features) labels_[id] = {segment, true, frame.t};
  }
  // Compared features of a found segment that no longer fit it, and all features of rejected
  // segments, lose their label. Ended tracks keep theirs for the frames they were seen in.
  std::set<int> on_found;
  for (const FoundPlane& plane : result.planes)
    on_found.insert(plane.features.begin(), plane.features.end());
  for (auto it = labels_.begin(); it != labels_.end();) {
    const int id = it->first, segment = it->second.segment;
    const bool lost =
        segments_[segment].rejected ||
        (matched.count(segment) && compared.count(id) && !on_found.count(id) && !moving.count(id));
    it = lost ? labels_.erase(it) : std::next(it);
  }
}

void PlaneDiscovery::adoptYoungTracks(const FeatureFrame& k, const FeatureFrame& reference) {
  std::set<int> judged, young;  // in the reference frame (judged by the check), and not
  for (const TrackedFeature& f : reference.features) judged.insert(f.id);
  for (const TrackedFeature& f : k.features)
    if (!judged.count(f.id)) young.insert(f.id);
  const auto& frames = history_.frames();
  for (size_t i = 0; i + 1 < frames.size() && !young.empty(); ++i) {
    std::set<int> born_here;  // the oldest frame of the history that holds them: the longest span
    for (const TrackedFeature& f : frames[i].frame.features)
      if (young.erase(f.id)) born_here.insert(f.id);
    if (!born_here.empty())
      adopt(frames[i].frame, k, history_.rotationFrom(frames[i]), judged, born_here);
  }
}

void PlaneDiscovery::adopt(const FeatureFrame& j, const FeatureFrame& k,
                           const Eigen::Matrix3d& R_kj, const std::set<int>& judged,
                           const std::set<int>& young) {
  std::vector<int> ids;
  std::vector<BearingPair> pairs = bearingPairs(j, k, R_kj, &ids);
  std::vector<size_t> labelled;  // on a confirmed segment, static in the last check
  std::map<int, std::vector<size_t>> members;
  for (size_t i = 0; i < pairs.size(); ++i)
    if (const auto it = labels_.find(ids[i]);
        judged.count(ids[i]) && it != labels_.end() && it->second.static_in_last_check) {
      const Segment& s = segments_.at(it->second.segment);
      if (!s.confirmed || s.rejected) continue;
      labelled.push_back(i);
      members[it->second.segment].push_back(i);
    }
  if (labelled.size() < options_.min_features) return;
  const auto parallax_px = [&](const std::vector<size_t>& of) {
    std::vector<double> flow;
    for (size_t i : of) flow.push_back(parallax(pairs[i]));
    return median(flow) * options_.focal_px;
  };
  if (parallax_px(labelled) < options_.min_parallax_px) return;
  std::vector<BearingPair> static_pairs;
  for (size_t i : labelled) static_pairs.push_back(pairs[i]);
  Eigen::Vector3d t = translationDirection(static_pairs);
  const Eigen::Matrix3d correction = refineRotation(pairs, labelled, t);
  for (BearingPair& p : pairs) p.rotated_j = correction * p.rotated_j;
  t = towardsScene(pairs, labelled, t);
  std::vector<double> distances;
  for (size_t i : labelled) distances.push_back(epipolarDistance(pairs[i], t));
  const double epipolar_limit = options_.epipolar_px / options_.focal_px;
  const double plane_limit = planeLimit(options_, distances);
  std::vector<std::pair<int, Eigen::Vector3d>> planes;  // segment, m'
  for (const auto& [segment, on_it] : members)
    if (on_it.size() >= options_.min_features && parallax_px(on_it) >= options_.min_parallax_px)
      if (const auto m = planeThroughPairs(pairs, on_it, t)) planes.push_back({segment, *m});
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (!young.count(ids[i])) continue;
    const bool moves = epipolarDistance(pairs[i], t) >= epipolar_limit;
    judged_[ids[i]] = {!moves, k.t};
    int best = 0;
    double best_error = plane_limit;
    if (!moves)
      for (const auto& [segment, m] : planes)
        if (const double e = transferError(pairs[i], t, m); e < best_error) {
          best = segment;
          best_error = e;
        }
    // Judged again each frame, over a longer span: a label is dropped when its plane no longer
    // fits (or the track moves), kept when its plane could not be judged here.
    const auto label = labels_.find(ids[i]);
    const bool own_plane_judged =
        label != labels_.end() && std::any_of(planes.begin(), planes.end(), [&](const auto& p) {
          return p.first == label->second.segment;
        });
    if (best != 0)
      labels_[ids[i]] = {best, true, k.t};
    else if (label != labels_.end() && (moves || own_plane_judged))
      labels_.erase(label);
  }
}

FeatureFrame PlaneDiscovery::label(const FeatureFrame& frame,
                                   const std::optional<Eigen::Quaterniond>& R_previous_current) {
  if (!options_.enabled) return FeatureFrame{frame.t, frame.image_t, {}};
  history_.push(frame, R_previous_current);
  if (const auto* reference = history_.reference(options_.span_s)) {
    const CheckResult result = check(reference->frame, frame, history_.rotationFrom(*reference));
    if (result.judged) {
      update(result, frame);
      if (options_.adopt_young) adoptYoungTracks(frame, reference->frame);
    }
  }
  history_.trim(options_.span_s);
  // Labels are kept for frames the initializer may still look at.
  for (const TrackedFeature& f : frame.features) {
    if (const auto it = labels_.find(f.id); it != labels_.end()) it->second.last_seen_t = frame.t;
    if (const auto it = judged_.find(f.id); it != judged_.end()) it->second.last_seen_t = frame.t;
  }
  forgetOlderThan(labels_, frame.t - kLabelMemoryS);
  forgetOlderThan(judged_, frame.t - kLabelMemoryS);
  return labelled(frame);
}

FeatureFrame PlaneDiscovery::labelled(const FeatureFrame& frame) const {
  FeatureFrame out;
  out.t = frame.t;
  out.image_t = frame.image_t;
  for (const TrackedFeature& f : frame.features) {
    TrackedFeature kept = f;
    kept.plane_id = 0;
    if (const auto it = labels_.find(f.id); it != labels_.end() && it->second.static_in_last_check)
      if (const Segment& s = segments_.at(it->second.segment); s.confirmed && !s.rejected)
        kept.plane_id = it->second.segment;
    if (kept.plane_id == 0) {
      const auto judged = judged_.find(f.id);
      if (!options_.static_points || judged == judged_.end() || !judged->second.on_epipolar_line)
        continue;
    }
    out.features.push_back(kept);
  }
  return out;
}

}  // namespace rpvio
