// The one options pattern (common/options.h): every field is a key of its own name, values are
// checked, describe() reads back to the same options, and unread keys are found.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/input_error.h"
#include "common/options.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

enum class Shape { kRound, kSquare };
const OptionNames<Shape> kShapeNames = {{"round", Shape::kRound}, {"square", Shape::kSquare}};

struct ToyOptions {
  double ratio = 0.1;
  int levels = 2;
  size_t budget = 150;
  bool enabled = true;
  std::string name = "toy";
  Shape shape = Shape::kRound;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, ratio);
    RPVIO_OPTION(v, levels);
    RPVIO_OPTION(v, budget);
    RPVIO_OPTION(v, enabled);
    RPVIO_OPTION(v, name);
    RPVIO_OPTION_CHOICE(v, shape, kShapeNames);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(levels <= 5, "levels", "must be at most 5");
  }
};

/// The InputError text of loading [Toy] from `text` ("" when it loads).
std::string loadError(const test::TempDir& dir, const std::string& text) {
  test::writeText(dir.file("toy.ini"), text);
  try {
    loadOptions<ToyOptions>(IniFile(dir.file("toy.ini")), "Toy");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Options, EveryFieldIsTheKeyOfItsName) {
  test::TempDir dir;
  test::writeText(dir.file("toy.ini"),
                  "[Toy]\nratio = 2.5e-3\nlevels = -3\nbudget = 7\nenabled = no\n"
                  "name = other\nshape = square\n[Other]\nratio = 9\n");
  const IniFile ini(dir.file("toy.ini"));
  const auto o = loadOptions<ToyOptions>(ini, "Toy");
  EXPECT_EQ(o.ratio, 2.5e-3);
  EXPECT_EQ(o.levels, -3);
  EXPECT_EQ(o.budget, 7u);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.name, "other");
  EXPECT_EQ(o.shape, Shape::kSquare);
  // [Other] was not read by anyone: its key is the one unread.
  const auto unread = ini.unreadKeys();
  ASSERT_EQ(unread.size(), 1u);
  EXPECT_EQ(unread[0].section, "Other");
  EXPECT_EQ(unread[0].key, "ratio");
  EXPECT_EQ(unread[0].line, 9);
  EXPECT_TRUE(ini.sectionAskedFor("Toy"));
  EXPECT_FALSE(ini.sectionAskedFor("Other"));
}

TEST(Options, AbsentKeysKeepTheirDefaults) {
  test::TempDir dir;
  test::writeText(dir.file("toy.ini"), "[Toy]\nlevels = 4\n");
  const auto o = loadOptions<ToyOptions>(IniFile(dir.file("toy.ini")), "Toy");
  EXPECT_EQ(o.levels, 4);
  EXPECT_EQ(o.ratio, ToyOptions{}.ratio);
  EXPECT_EQ(o.name, "toy");
  EXPECT_EQ(o.shape, Shape::kRound);
}

TEST(Options, BadValuesNameTheFileTheLineAndWhatIsExpected) {
  test::TempDir dir;
  const std::string file = dir.file("toy.ini");
  EXPECT_EQ(loadError(dir, "[Toy]\nlevels = 2.5\n"),
            file + ":line 2: levels must be a whole number");
  EXPECT_EQ(loadError(dir, "[Toy]\n\nbudget = -1\n"),
            file + ":line 3: budget must be a non-negative whole number");
  EXPECT_EQ(loadError(dir, "[Toy]\nshape = oval\n"),
            file + ":line 2: shape must be one of round, square, not 'oval'");
  EXPECT_EQ(loadError(dir, "[Toy]\nlevels = 6\n"), file + ":line 2: levels must be at most 5");
  EXPECT_NE(loadError(dir, "[Toy]\nratio = fast\n").find(file + ":line 2:"), std::string::npos);
  EXPECT_NE(loadError(dir, "[Toy]\nenabled = maybe\n").find(file + ":line 2:"), std::string::npos);
  EXPECT_EQ(loadError(dir, "[Toy]\nratio = 1\nratio = 2\n"),
            file + ":line 3: 'ratio' given twice in [Toy] (first on line 2)");
}

TEST(Options, DescribeReadsBackToTheSameOptions) {
  ToyOptions o;
  o.ratio = 0.1 + 0.2;  // not the double nearest 0.3
  o.levels = -1;
  o.budget = 12345;
  o.enabled = false;
  o.shape = Shape::kSquare;
  const std::string text = describeOptions(o);
  EXPECT_EQ(text,
            "ratio = 0.30000000000000004\nlevels = -1\nbudget = 12345\nenabled = false\n"
            "name = toy\nshape = square\n");
  test::TempDir dir;
  test::writeText(dir.file("toy.ini"), "[Toy]\n" + text);
  const auto back = loadOptions<ToyOptions>(IniFile(dir.file("toy.ini")), "Toy");
  EXPECT_EQ(describeOptions(back), text);
}

TEST(Options, NumbersAreWrittenShortAndExact) {
  EXPECT_EQ(exactNumberText(0.1), "0.1");
  EXPECT_EQ(exactNumberText(5e-3), "0.005");
  EXPECT_EQ(exactNumberText(460), "460");
  EXPECT_EQ(exactNumberText(2000), "2000");
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-12, 12), mantissa(-1, 1);
  for (int k = 0; k < 10000; ++k) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    EXPECT_EQ(std::strtod(exactNumberText(x).c_str(), nullptr), x) << exactNumberText(x);
  }
}

}  // namespace
}  // namespace rpvio
