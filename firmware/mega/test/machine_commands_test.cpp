// The command table against protocol/mega.md: every command the spec's tables name has a row, and
// every row is a command the spec names; the flags say which run beside a long command or a stream.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "machine.h"

using namespace mega;

namespace {

uv::Command command(char letter, uint16_t code) {
  uv::Command c{};
  c.letter = letter;
  c.code = code;
  return c;
}

// Each `G<n>` or `M<n>` in the first cell of a table row of mega.md.
std::set<std::string> specCommands() {
  std::ifstream in(UV_MEGA_MD);
  std::set<std::string> names;
  std::string line;
  const std::regex word(R"(`([GM])(\d+))"), alias(R"(= `?([GM])(\d+))");
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    std::string first = line.substr(0, line.find(" |", 2));
    for (std::sregex_iterator m(first.begin(), first.end(), word), end; m != end; ++m) names.insert((*m)[1].str() + (*m)[2].str());
    // "`M17` / `M18` (= `M84`)": the alias is named without a backtick after its '='.
    for (std::sregex_iterator m(first.begin(), first.end(), alias), end; m != end; ++m)
      names.insert((*m)[1].str() + (*m)[2].str());
  }
  return names;
}

}  // namespace

TEST(CommandTable, HasARowForEveryCommandMegaMdNamesAndNoOther) {
  const std::set<std::string> spec = specCommands();
  ASSERT_GT(spec.size(), 40u) << "mega.md's tables were not read";
  std::set<std::string> table;
  for (char letter : {'G', 'M'})
    for (uint16_t code = 0; code < 2000; code++)
      if (Machine::knows(command(letter, code))) table.insert(letter + std::to_string(code));
  EXPECT_EQ(table, spec);
}

TEST(CommandTable, QueriesRunBesideALongCommandAndStreamCommandsBetweenRecords) {
  std::set<std::string> query, stream, halted;
  for (char letter : {'G', 'M'})
    for (uint16_t code = 0; code < 2000; code++) {
      uint8_t f = Machine::commandFlags(command(letter, code));
      std::string name = letter + std::to_string(code);
      if (f & Machine::kQuery) query.insert(name);
      if (f & Machine::kStream) stream.insert(name);
      if (f & Machine::kWhileHalted) halted.insert(name);
    }
  EXPECT_EQ(query, (std::set<std::string>{"M105", "M114", "M115", "M154", "M155", "M27"}));
  EXPECT_EQ(stream, (std::set<std::string>{"M105", "M114", "M115", "M154", "M155", "M24", "M25", "M27", "M524"}));
  EXPECT_EQ(halted, (std::set<std::string>{"M112", "M999"}));
}
