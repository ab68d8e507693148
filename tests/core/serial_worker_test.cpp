// SerialWorker: tasks run one at a time in the order handed over, an exception reaches only its
// task's future, and the destructor runs what is still queued.
#include "mrpt_modules/core/serial_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace rpvio {
namespace {

TEST(SerialWorker, RunsTasksOneAtATimeInOrder) {
  std::vector<int> order;  // written by the worker only
  std::atomic<int> running{0};
  bool overlapped = false;
  std::vector<std::future<int>> results;
  {
    SerialWorker worker;
    for (int k = 0; k < 50; ++k)
      results.push_back(worker.submit([&, k] {
        if (running.fetch_add(1) != 0) overlapped = true;
        if (k % 7 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        order.push_back(k);
        running.fetch_sub(1);
        return k * k;
      }));
    EXPECT_EQ(results[10].get(), 100);
  }
  ASSERT_EQ(order.size(), 50u);  // the destructor ran the rest
  for (int k = 0; k < 50; ++k) EXPECT_EQ(order[size_t(k)], k);
  EXPECT_FALSE(overlapped);
  EXPECT_EQ(results[49].get(), 49 * 49);
}

TEST(SerialWorker, AnExceptionReachesOnlyItsTasksFuture) {
  SerialWorker worker;
  auto failing = worker.submit([]() -> int { throw std::runtime_error("bad image"); });
  auto next = worker.submit([] { return 7; });
  EXPECT_THROW(failing.get(), std::runtime_error);
  EXPECT_EQ(next.get(), 7);
}

}  // namespace
}  // namespace rpvio
