#include "mrpt_modules/loop/keyframe_database.h"

#include <algorithm>

namespace rpvio {

void KeyframeDatabase::add(const BowVector& bow) {
  const size_t index = vectors_.size();
  vectors_.push_back(bow);
  for (const auto& [word, weight] : bow) inverted_[word].push_back({index, weight});
}

std::vector<DatabaseMatch> KeyframeDatabase::query(const BowVector& bow, size_t before,
                                                   double min_score) const {
  // bowScore as a sum over the shared words of min(a_w, b_w), accumulated word by word.
  std::vector<double> scores(std::min(before, vectors_.size()), 0.0);
  for (const auto& [word, weight] : bow) {
    const auto it = inverted_.find(word);
    if (it == inverted_.end()) continue;
    for (const Posting& p : it->second) {
      if (p.keyframe >= scores.size()) break;  // postings are in insertion order
      scores[p.keyframe] += std::min(weight, p.weight);
    }
  }
  std::vector<DatabaseMatch> matches;
  for (size_t k = 0; k < scores.size(); ++k)
    if (scores[k] >= min_score && scores[k] > 0) matches.push_back({k, scores[k]});
  std::stable_sort(
      matches.begin(), matches.end(),
      [](const DatabaseMatch& a, const DatabaseMatch& b) { return a.score > b.score; });
  return matches;
}

void KeyframeDatabase::clear() {
  vectors_.clear();
  inverted_.clear();
}

}  // namespace rpvio
