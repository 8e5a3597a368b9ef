// The engine's message wordings: said with arguments and recognised again, unambiguously.
#include "common/message.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <set>
#include <vector>
#include <stdexcept>
#include <string>

namespace hdrf {
namespace {

int Arguments(const Wording& w) {
  int n = 0;
  const std::string s = w.english;
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
    if (s[i] == '%' && s[i + 1] >= '1' && s[i + 1] <= '9') ++n;
  return n;
}

// Arguments as the engine gives them: numbers, a channel letter, a path with spaces and
// colons, a message within the message.
std::string Sample(int k) {
  switch (k % 4) {
    case 0: return std::to_string(17 + k);
    case 1: return "0." + std::to_string(25 + k);
    case 2: return "/data/my scans: " + std::to_string(k) + "/sensor.json";
    default: return Say(words::kFlicker, {std::to_string(k)});
  }
}

TEST(Messages, EveryWordingIsRecognisedWithItsArgumentsAgain) {
  ASSERT_GE(AllWordings().size(), 40u);
  std::set<std::string> names, texts;
  for (const Wording* w : AllWordings()) {
    EXPECT_TRUE(names.insert(w->name).second) << w->name;
    EXPECT_TRUE(texts.insert(w->english).second) << "two wordings alike: " << w->name;
    const int n = Arguments(*w);
    // Each of %1..%n used once.
    for (int k = 1; k <= n; ++k)
      EXPECT_NE(std::string(w->english).find("%" + std::to_string(k)), std::string::npos) << w->name << " %" << k;
    std::vector<std::string> args;
    for (int k = 0; k < n; ++k) args.push_back(Sample(k));
    std::string said;
    switch (n) {
      case 0: said = Say(*w); break;
      case 1: said = Say(*w, {args[0]}); break;
      case 2: said = Say(*w, {args[0], args[1]}); break;
      case 3: said = Say(*w, {args[0], args[1], args[2]}); break;
      case 4: said = Say(*w, {args[0], args[1], args[2], args[3]}); break;
      case 5: said = Say(*w, {args[0], args[1], args[2], args[3], args[4]}); break;
      case 6: said = Say(*w, {args[0], args[1], args[2], args[3], args[4], args[5]}); break;
      case 8: said = Say(*w, {args[0], args[1], args[2], args[3], args[4], args[5], args[6], args[7]}); break;
      default: FAIL() << w->name << " has " << n << " arguments; extend this test";
    }
    EXPECT_EQ(said.find('%' + std::string("1")), std::string::npos) << said;
    const auto parsed = ParseMessage(said);
    ASSERT_TRUE(parsed) << w->name << ": " << said;
    EXPECT_STREQ(parsed->wording->name, w->name) << said;
    EXPECT_EQ(parsed->args, args) << said;
  }
}

TEST(Messages, TheEnglishTextIsTheWordingWithItsArguments) {
  EXPECT_EQ(Say(words::kFewPixelsMatched, {"12"}), "only 12 % of pixels matched");
  EXPECT_EQ(Say(words::kConfirmingPose, {"2", "3"}), "confirming the pose after a loss (2 of 3 frames)");
  EXPECT_EQ(Say(words::kIcpResidualHigh, {Num(3.14159, 1), Num(2.5, 1), Num(0.8, 1)}),
            "point-to-surface error 3.1 cm, 2.5x the scan's usual 0.8 cm");
  EXPECT_EQ(Sig(12.5), "12.5");
  EXPECT_EQ(Sig(0.3333333), "0.3333");
  EXPECT_EQ(Num(1.0 / 3, 2), "0.33");
  // The wrong number of arguments is a programming error, caught where it is made.
  EXPECT_THROW(Say(words::kFewPixelsMatched), std::logic_error);
  EXPECT_THROW(Say(words::kNoCorrespondences, {"x"}), std::logic_error);
}

TEST(Messages, OtherTextIsNotTakenForAWording) {
  EXPECT_FALSE(ParseMessage(""));
  EXPECT_FALSE(ParseMessage("/data/seq/rgb.txt:3: expected 'timestamp filename'"));
  EXPECT_FALSE(ParseMessage("only  % of pixels matched"));  // an argument is never empty
  EXPECT_FALSE(ParseMessage("only 12 % of pixels matched, and more"));
  EXPECT_FALSE(ParseMessage("no correspondences "));
  // A hostile text full of a wording's fixed pieces ends in bounded time, unrecognised.
  std::string hostile = "At ";
  for (int i = 0; i < 2000; ++i) hostile += " ms (step  of ) ,  times in a row.  The ";
  hostile += " steps captured so far are kept in .";
  EXPECT_FALSE(ParseMessage(hostile));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// docs/faq.md has an entry for every wording a user can meet: its first fixed fragment of
// ten characters or more (text between the arguments) appears in the page, with the page's
// *N* standing for an argument. A wording added without its entry fails here.
TEST(Messages, EveryWordingHasAnEntryInTheFaq) {
  std::ifstream in(HDRF_DOCS_DIR "/faq.md");
  ASSERT_TRUE(in) << HDRF_DOCS_DIR "/faq.md";
  std::string faq((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t i; (i = faq.find('`')) != std::string::npos;) faq.erase(i, 1);
  int checked = 0;
  for (const Wording* w : AllWordings()) {
    std::vector<std::string> fragments;
    std::string cur;
    const std::string s = w->english;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] == '%' && i + 1 < s.size() && s[i + 1] >= '1' && s[i + 1] <= '9') {
        fragments.push_back(cur);
        cur.clear();
        ++i;
      } else {
        cur += s[i];
      }
    }
    fragments.push_back(cur);
    std::string first;
    for (std::string f : fragments) {
      while (!f.empty() && std::string(" :,.()").find(f.front()) != std::string::npos) f.erase(0, 1);
      while (!f.empty() && std::string(" :,.()").find(f.back()) != std::string::npos) f.pop_back();
      if (f.size() >= 10) {
        first = f.substr(0, 40);
        break;
      }
    }
    if (first.empty()) first = s;
    EXPECT_NE(faq.find(first), std::string::npos) << w->name << ": no entry for \"" << first << "\" in docs/faq.md";
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

}  // namespace
}  // namespace hdrf
