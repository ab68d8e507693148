// The suite's sequence names: what each contains, and which the profiles write.
#include <gtest/gtest.h>

#include "sim/sequence_name.h"

namespace rpvio::sim {
namespace {

TEST(SequenceName, NamesSayWhatMoves) {
  EXPECT_EQ(parseSequenceName("static")->characters, 0);
  EXPECT_FALSE(parseSequenceName("static")->moving_objects);
  EXPECT_EQ(parseSequenceName("C8")->characters, 8);
  EXPECT_FALSE(parseSequenceName("C8")->moving_objects);
  EXPECT_TRUE(parseSequenceName("MP")->moving_objects);
  EXPECT_EQ(parseSequenceName("MP")->characters, 0);
  EXPECT_TRUE(parseSequenceName("MP-C4")->moving_objects);
  EXPECT_EQ(parseSequenceName("MP-C4")->characters, 4);
  for (const char* bad : {"", "C", "C-1", "c4", "MPC4", "MP-", "MP-static", "C12345", "walls"})
    EXPECT_FALSE(parseSequenceName(bad)) << bad;
}

TEST(SequenceName, MpSequencesCarryTrucksAndPanels) {
  const SimConfig mp = withSequenceContent(SimConfig::profile("hard"), *parseSequenceName("MP-C4"));
  EXPECT_EQ(mp.scene.characters, 4);
  EXPECT_EQ(mp.scene.pallet_trucks, kSuitePalletTrucks);
  EXPECT_EQ(mp.scene.sliding_panels, kSuiteSlidingPanels);
  const SimConfig c4 = withSequenceContent(SimConfig::profile("hard"), *parseSequenceName("C4"));
  EXPECT_EQ(c4.scene.pallet_trucks, 0);
}

TEST(SequenceName, TheHardSuiteAddsTheMovingPlaneSequences) {
  const std::vector<std::string> paper = {"static", "C1", "C2", "C4", "C6", "C8"};
  EXPECT_EQ(suiteSequences("paper"), paper);
  std::vector<std::string> hard = paper;
  hard.insert(hard.end(), {"MP", "MP-C4"});
  EXPECT_EQ(suiteSequences("hard"), hard);
}

}  // namespace
}  // namespace rpvio::sim
