// The bound on TOML nesting checked before toml++ parses (src/io/toml_nesting.hpp):
// a header or key of too many dotted parts and brackets nested too deep are
// refused at their line and column; dots in strings, comments, numbers and
// dates, and ordinary scene files, pass.
#include <string>

#include <gtest/gtest.h>

#include <impactlab/io/toml_nesting.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::check_toml_nesting;

std::string repeated(const std::string& part, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += part;
  return text;
}

// "LINE:COLUMN: description" of the refusal, or "passed"
std::string refusal(const std::string& text) {
  try {
    check_toml_nesting(text, "scene.toml");
  } catch (const toml::parse_error& error) {
    return std::to_string(error.source().begin.line) + ":" + std::to_string(error.source().begin.column) +
           ": " + std::string(error.description());
  }
  return "passed";
}

TEST(TomlNesting, ManyDottedPartsAreRefusedWhereTheKeyBegins) {
  EXPECT_EQ(refusal("a = 1\n[x" + repeated(".x", 99999) + "]\n"), "2:2: a key of more than 32 dotted parts");
  EXPECT_EQ(refusal("x" + repeated(".x", 40) + " = 1\n"), "1:1: a key of more than 32 dotted parts");
  EXPECT_EQ(refusal("[x" + repeated(".x", 31) + "]\n"), "passed");
}

TEST(TomlNesting, DeepBracketsAreRefused) {
  EXPECT_EQ(refusal("a = " + repeated("[", 100000) + "\n"), "1:37: brackets nested more than 32 deep");
  EXPECT_EQ(refusal("a = " + repeated("{b = ", 40) + "1" + repeated("}", 40) + "\n"),
            "1:165: brackets nested more than 32 deep");
  EXPECT_EQ(refusal("a = " + repeated("[", 20) + "1" + repeated("]", 20) + "\n"), "passed");
}

TEST(TomlNesting, DotsInStringsCommentsAndNumbersPass) {
  const std::string text = "name = \"" + repeated("a.", 1000) + "\"\n"
                           "literal = '" + repeated("b.", 1000) + "'\n"
                           "multi = \"\"\"\n" + repeated("c.", 1000) + "\n\"\"\"\n"
                           "# " + repeated("d.", 1000) + "\n"
                           "values = [1.5, 2.5, 1979-05-27T07:32:00.999]\n"
                           "escaped = \"\\\"" + repeated(".", 100) + "\"\n";
  EXPECT_EQ(refusal(text), "passed");
}

}  // namespace
