// "Did you mean": the closest known names to an unknown one, by edit
// distance ignoring case, within max(2, length / 3) edits.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/closest_names.h"

namespace rbsim {
namespace {

TEST(ClosestNames, EditDistanceIgnoresCase) {
  EXPECT_EQ(editDistanceIgnoringCase("", ""), 0u);
  EXPECT_EQ(editDistanceIgnoringCase("", "abc"), 3u);
  EXPECT_EQ(editDistanceIgnoringCase("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistanceIgnoringCase("Arm/Joint1", "arm/joint1"), 0u);
  EXPECT_EQ(editDistanceIgnoringCase("axel", "axle"), 2u);  // a transposition is two edits
  EXPECT_EQ(editDistanceIgnoringCase("arm/joint", "arm/joint2"), 1u);
}

TEST(ClosestNames, SuggestsUpToThreeClosestFirstWithinReach) {
  const std::vector<std::string> joints = {"arm/joint1", "arm/joint2", "arm/joint3", "arm/joint4", "gripper"};
  // Four are one edit away: the three first alphabetically.
  EXPECT_EQ(closestNames("arm/joint5", joints), (std::vector<std::string>{"arm/joint1", "arm/joint2", "arm/joint3"}));
  EXPECT_EQ(closestNames("arm/joint22", joints, 1), (std::vector<std::string>{"arm/joint2"}));
  EXPECT_EQ(closestNames("GRIPER", joints), (std::vector<std::string>{"gripper"}));
  // A short name still reaches two edits; nothing near is nothing.
  EXPECT_EQ(closestNames("lft", {"lift", "left", "wheel"}), (std::vector<std::string>{"left", "lift"}));
  EXPECT_TRUE(closestNames("nosuch", joints).empty());
  EXPECT_TRUE(closestNames("", joints).empty());
  EXPECT_TRUE(closestNames("x", {}).empty());
  // joint1 is 4 edits from arm/joint1, more than a third of its 6 letters.
  EXPECT_TRUE(closestNames("joint1", joints).empty());
  // Duplicates in the list are named once.
  EXPECT_EQ(closestNames("box", {"box1", "box1"}), (std::vector<std::string>{"box1"}));
  // A huge name gets no search at all.
  EXPECT_TRUE(closestNames(std::string(kMaxSuggestedNameLength + 1, 'a'),
                           {std::string(kMaxSuggestedNameLength, 'a')})
                  .empty());
}

TEST(ClosestNames, DidYouMeanReadsAsASentence) {
  EXPECT_EQ(didYouMean("nosuch", {"axle"}), "");
  EXPECT_EQ(didYouMean("axel", {"axle", "weld"}), " (did you mean 'axle'?)");
  EXPECT_EQ(didYouMean("box", {"box1", "box2"}), " (did you mean 'box1' or 'box2'?)");
  EXPECT_EQ(didYouMean("box", {"box3", "box1", "box2", "box4"}), " (did you mean 'box1', 'box2' or 'box3'?)");
}

}  // namespace
}  // namespace rbsim
