#include "evaluation/association.h"

#include <cmath>

namespace rpvio::eval {

Association associateByTime(const Trajectory& gt, const Trajectory& est, double max_dt) {
  Association pairs;
  size_t g = 0;
  long last_used = -1;
  for (size_t e = 0; e < est.size(); ++e) {
    const double t = est[e].t;
    // Advance while the next ground-truth stamp is at least as close.
    while (g + 1 < gt.size() && std::abs(gt[g + 1].t - t) <= std::abs(gt[g].t - t)) ++g;
    if (gt.empty() || std::abs(gt[g].t - t) > max_dt || static_cast<long>(g) == last_used) continue;
    pairs.emplace_back(g, e);
    last_used = static_cast<long>(g);
  }
  return pairs;
}

Association associateByIndex(const Trajectory& gt, const Trajectory& est) {
  Association pairs;
  for (size_t i = 0; i < std::min(gt.size(), est.size()); ++i) pairs.emplace_back(i, i);
  return pairs;
}

}  // namespace rpvio::eval
