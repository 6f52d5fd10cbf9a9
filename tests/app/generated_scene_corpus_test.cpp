// The generated part of issue 17's bad-input corpus: every numeric key of every shipped example
// scene (examples/*.toml), in turn set to a value the numerics cannot bear or to the wrong type,
// and run through the command the scene is for. Each case must give exit 2 with the key's name in
// the message, nothing non-finite in stdout, no database created by a wear scene (validation
// comes before any work), and the scene file byte-identical afterwards. The hand-written classes
// of the issue (crashes, journals, kills, profiles) are in bad_input_corpus_test.cpp.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/app/cli_runner.h"

namespace railwear::test {
namespace {

// Non-finite, beyond any physical range in either direction, and two wrong types.
const char* const kBadValues[] = {"nan", "inf", "-inf", "1e308", "-1e308", "\"text\"", "true"};

struct SceneCase {
  const char* file;     // in examples/
  const char* command;  // "contact" or "wear"
};

const SceneCase kScenes[] = {
    {"gauge_corner.toml", "contact"},        {"tread.toml", "contact"},
    {"rolling_gauge_corner.toml", "contact"}, {"rolling_flange.toml", "contact"},
    {"wheelset.toml", "contact"},            {"groove_conformal.toml", "contact"},
    {"wear_high_rail.toml", "wear"},         {"curve_r600_vehicles.toml", "wear"},
    {"curve_r600_mbs_collective.toml", "wear"}, {"wear_wheel_coevolution.toml", "wear"},
    {"curve_r600_wheel_wear.toml", "wear"},
};

class GeneratedSceneCorpus : public CliFixture,
                             public ::testing::WithParamInterface<SceneCase> {};

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

TEST_P(GeneratedSceneCorpus, EveryNumericKeyRefusesNonFiniteHugeAndWrongTypedValues) {
  const SceneCase scene = GetParam();
  const fs::path examples = fs::path(RAILWEAR_SOURCE_DIR) / "examples";
  // The scene's relative references (profiles, collectives) resolve beside it: link examples/'s
  // entries into the working directory.
  for (const auto& entry : fs::directory_iterator(examples)) {
    fs::create_symlink(entry.path(), dir_ / entry.path().filename());
  }
  const std::vector<std::string> lines = Lines(ReadFile(examples / scene.file));
  // Every `key = number` of a line, a table's key or one inside an inline table (arrays are left
  // to the hand-written corpus).
  const std::regex numeric(R"(([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(-?[0-9][0-9_.eE+-]*)(?=\s*(,|\}|#|$)))");
  const std::regex non_finite(R"(\b(nan|inf)\b)", std::regex::icase);
  int keys = 0, cases = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find_first_not_of(" \t") != std::string::npos &&
        lines[i][lines[i].find_first_not_of(" \t")] == '#') {
      continue;  // a comment
    }
    for (auto it = std::sregex_iterator(lines[i].begin(), lines[i].end(), numeric);
         it != std::sregex_iterator(); ++it) {
      const std::smatch& m = *it;
      ++keys;
      const std::string key = m[1];
      for (const char* bad : kBadValues) {
        std::string edited = lines[i];
        edited.replace(m.position(2), m.length(2), bad);
        std::string text;
        for (size_t j = 0; j < lines.size(); ++j) text += (j == i ? edited : lines[j]) + "\n";
        std::ofstream(dir_ / "case.toml") << text;
        const std::string what = std::string(scene.file) + ":" + std::to_string(i + 1) + " " +
                                 key + " = " + bad;
        const Outcome o = Run(std::string(scene.command) + " case.toml" +
                              (std::string(scene.command) == "wear" ? " --db case.sqlite" : ""));
        ++cases;
        EXPECT_EQ(o.exit_code, 2) << what << "\n" << o.err;
        EXPECT_NE(o.err.find(key), std::string::npos) << what << ": the message names no key\n"
                                                       << o.err;
        EXPECT_FALSE(std::regex_search(o.out, non_finite)) << what << "\n" << o.out;
        EXPECT_FALSE(fs::exists(dir_ / "case.sqlite")) << what << ": a database was created";
        EXPECT_EQ(ReadFile(dir_ / "case.toml"), text) << what;
        fs::remove(dir_ / "case.sqlite");
      }
    }
  }
  std::printf("[ measured ] %s: %d numeric keys, %d generated cases\n", scene.file, keys, cases);
  EXPECT_GT(keys, 0) << scene.file << ": no numeric key found (the generator's pattern)";
}

INSTANTIATE_TEST_SUITE_P(Examples, GeneratedSceneCorpus, ::testing::ValuesIn(kScenes),
                         [](const ::testing::TestParamInfo<SceneCase>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace railwear::test
