// The bus's retained messages: a module listed after the one that published a retained message
// (MapReady) still receives it when it subscribes; other messages are not kept.
#include <gtest/gtest.h>

#include <vector>

#include "mrpt_modules/core/bus.h"

namespace rpvio {
namespace {

struct Kept {
  int value = 0;
};
struct Passing {
  int value = 0;
};

TEST(Bus, ARetainedMessageReachesLaterSubscribersOnceAndThenFollowsLikeAnyOther) {
  Bus bus;
  std::vector<int> early, late;
  bus.subscribe<Kept>([&](const Kept& k) { early.push_back(k.value); });
  bus.publishRetained(Kept{1});
  bus.publishRetained(Kept{2});
  bus.publish(Passing{7});
  bus.subscribe<Kept>([&](const Kept& k) { late.push_back(k.value); });
  bool passing_seen = false;
  bus.subscribe<Passing>([&](const Passing&) { passing_seen = true; });
  EXPECT_EQ(early, (std::vector<int>{1, 2}));
  EXPECT_EQ(late, (std::vector<int>{2}));  // the last one only
  EXPECT_FALSE(passing_seen);
  bus.publish(Kept{3});
  EXPECT_EQ(late, (std::vector<int>{2, 3}));
}

}  // namespace
}  // namespace rpvio
