// The settings registry: every engine setting declared once, with a default that passes
// its own checks, a range that is enforced, and a text form that round-trips.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "common/error.h"
#include "pipeline/settings.h"
#include "support/test_support.h"

namespace hdrf::pipeline {
namespace {

std::string Text(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

TEST(Settings, EveryKeyAndAliasIsUniqueAndEveryDefaultIsValid) {
  std::set<std::string> names;
  for (const Setting& s : Settings()) {
    EXPECT_TRUE(names.insert("--" + s.key).second) << s.key;
    if (!s.alias.empty()) EXPECT_TRUE(names.insert(s.alias).second) << s.alias;
    EXPECT_FALSE(s.help.empty()) << s.key;
    // The default, set back through the registry, leaves the default.
    PipelineOptions o;
    EXPECT_NO_THROW(s.set(o, s.Default())) << s.key;
    EXPECT_EQ(s.get(o), s.Default()) << s.key;
  }
  EXPECT_GE(Settings().size(), 30u);
  EXPECT_NO_THROW(PipelineOptions{}.Check());
}

// The studio labels every control in plain words and says when to change it: each setting
// has its own label (no two alike, none the bare key) and advice.
TEST(Settings, EverySettingHasPlainWordsAndAdvice) {
  std::set<std::string> labels;
  for (const Setting& s : Settings()) {
    EXPECT_GE(s.label.size(), 3u) << s.key;
    EXPECT_EQ(s.label.find('_'), std::string::npos) << s.key << ": " << s.label;
    EXPECT_NE(s.label, s.key);
    EXPECT_TRUE(labels.insert(s.label).second) << s.key << " repeats the label " << s.label;
    EXPECT_GE(s.advice.size(), 10u) << s.key;
  }
}

// Each setting reaches its own field and no other: set a non-default value, read it back,
// and check every other setting still has its default.
TEST(Settings, EachSettingSetsExactlyItsOwnField) {
  for (const Setting& s : Settings()) {
    std::string value;
    switch (s.kind) {
      case SettingKind::kBool: value = s.Default() == "true" ? "false" : "true"; break;
      case SettingKind::kChoice: value = s.choices.back() == s.Default() ? s.choices.front() : s.choices.back(); break;
      case SettingKind::kIntList: value = "3,2"; break;
      default: value = s.Default() == Text(s.max) ? Text(s.min) : Text(s.max);
    }
    PipelineOptions o;
    s.set(o, value);
    EXPECT_NE(s.get(o), s.Default()) << s.key << " = " << value;
    for (const Setting& other : Settings())
      if (&other != &s) EXPECT_EQ(other.get(o), other.Default()) << s.key << " changed " << other.key;
  }
}

TEST(Settings, BadValuesAreRefusedNamingTheKey) {
  PipelineOptions o;
  test::ExpectErrorContaining([&] { FindSetting("volume.voxel_m").set(o, "2"); },
                              {"'volume.voxel_m'", "out of range", "0.001 .. 1 m"});
  test::ExpectErrorContaining([&] { FindSetting("volume.voxel_m").set(o, "1 cm"); }, {"'volume.voxel_m'", "not a number"});
  test::ExpectErrorContaining([&] { FindSetting("volume.voxel_m").set(o, "nan"); }, {"'volume.voxel_m'", "not a number"});
  // The fixed cube's settings are gone; asking for them says what replaced them.
  test::ExpectErrorContaining([&] { FindSetting("volume.resolution"); }, {"'volume.resolution'", "volume.voxel_m"});
  test::ExpectErrorContaining([&] { FindSetting("volume.size_m"); }, {"'volume.size_m'", "no fixed extent"});
  test::ExpectErrorContaining([&] { FindSetting("volume.max_memory_mb").set(o, "1e308"); },
                              {"'volume.max_memory_mb'", "out of range"});
  test::ExpectErrorContaining([&] { FindSetting("tracker.kind").set(o, "orb"); }, {"'tracker.kind'", "one of"});
  test::ExpectErrorContaining([&] { FindSetting("depth.bilateral").set(o, "maybe"); }, {"'depth.bilateral'"});
  test::ExpectErrorContaining([&] { FindSetting("tracker.iterations").set(o, "1,2,3,4,5"); },
                              {"'tracker.iterations'", "1 to 4"});
  test::ExpectErrorContaining([&] { FindSetting("volume.resolutoin"); }, {"'volume.resolutoin'", "unknown setting"});
  // Nothing was changed by the refused values.
  for (const Setting& s : Settings()) EXPECT_EQ(s.get(o), s.Default()) << s.key;
  // Cross-field checks stay with the options structs, and name the key too.
  o.volume.encoding = volume::VoxelEncoding::kCompact;
  FindSetting("volume.max_weight").set(o, "100");
  test::ExpectErrorContaining([&] { o.Check(); }, {"'volume.max_weight'", "65"});
  // No iteration on the finest level: every pose would be the prediction (it was taken).
  PipelineOptions none;
  FindSetting("tracker.iterations").set(none, "0,0,0");
  test::ExpectErrorContaining([&] { none.Check(); }, {"'tracker.iterations'", "finest level (the last of 3)"});
  FindSetting("tracker.iterations").set(none, "0,0,5");
  EXPECT_NO_THROW(none.Check());
}

}  // namespace
}  // namespace hdrf::pipeline
