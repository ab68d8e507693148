#pragma once
// Row-parallel loops of the image passes (renderer, motion blur): deterministic whatever the thread
// count, since every row is computed by one thread on its own.
#include <algorithm>
#include <thread>
#include <vector>

namespace rpvio::sim {

/// Runs body(row) for every row, split over threads (0: all hardware threads) in interleaved
/// blocks.
template <typename Body>
void parallelRows(int rows, int threads, Body body) {
  const int n = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> workers;
  for (int w = 0; w < n; ++w)
    workers.emplace_back([=] {
      for (int r = w; r < rows; r += n) body(r);
    });
  for (auto& t : workers) t.join();
}

}  // namespace rpvio::sim
