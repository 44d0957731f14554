// The one JSON reader of the project (io/json_file.hpp): a repeated key, a number beyond a
// double and a folder are refused with the file, the key path and what was expected.

#include "io/json_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/test_support.hpp"

namespace vcontact::io {
namespace {

namespace fs = std::filesystem;

std::string written(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("vcontact_json_file_test_" + name);
  std::ofstream(p) << text;
  return p.string();
}

std::string errorOf(const std::string& path) {
  return test::inputErrorMessage([&] { readJsonFile(path); });
}

TEST(JsonFile, ARepeatedKeyIsRefusedWithItsPath) {
  const std::string top = written("top.json", R"({"duration": 0.01, "duration": 100})");
  EXPECT_NE(errorOf(top).find(top + ": duration: the key appears twice"), std::string::npos)
      << errorOf(top);
  const std::string deep =
      written("deep.json", R"({"bodies": [{"name": "a"}, {"name": "b", "pose": "0,0,0",
                                "name": "c"}]})");
  EXPECT_NE(errorOf(deep).find(": bodies[1].name: the key appears twice"), std::string::npos)
      << errorOf(deep);
  // The same key in two different objects is no repetition.
  const std::string fine =
      written("fine.json", R"({"a": {"x": 1}, "b": {"x": 2}, "x": [{"x": 3}]})");
  EXPECT_EQ(readJsonFile(fine)["b"]["x"], 2);
  fs::remove(top);
  fs::remove(deep);
  fs::remove(fine);
}

TEST(JsonFile, ANumberBeyondADoubleIsRefusedWithItsPath) {
  const std::string big = written("big.json", R"({"effects": {"stiffness": {"kv": 1e400}}})");
  EXPECT_NE(
      errorOf(big).find(": effects.stiffness.kv: a number beyond the range of a double ('1e400'"),
      std::string::npos)
      << errorOf(big);
  const std::string inArray = written("array.json", R"({"pose": [0, -1e999, 0]})");
  EXPECT_NE(errorOf(inArray).find(": pose[1]: a number beyond"), std::string::npos)
      << errorOf(inArray);
  // The largest and smallest doubles are numbers like any other.
  const std::string edge = written("edge.json", R"({"a": 1.7976931348623157e308, "b": 5e-324})");
  EXPECT_EQ(readJsonFile(edge)["a"].get<double>(), 1.7976931348623157e308);
  fs::remove(big);
  fs::remove(inArray);
  fs::remove(edge);
}

TEST(JsonFile, AFolderOrAMissingFileIsNamed) {
  const std::string folder = fs::temp_directory_path().string();
  EXPECT_EQ(errorOf(folder), folder + ": is a folder; expected a JSON file");
  const std::string missing = folder + "/vcontact_json_file_test_missing.json";
  EXPECT_EQ(errorOf(missing), missing + ": no such file");
}

// Issue 36: a file name with a byte of another encoding made nlohmann's dump throw (an
// internal error after a whole run). Each invalid byte becomes U+FFFD; valid UTF-8 is kept.
TEST(JsonFile, TextThatIsNotUtf8IsWrittenWithTheReplacementCharacter) {
  const nlohmann::json j = {{"file", "caf\xe9.json"}, {"name", "caf\xc3\xa9"}};
  EXPECT_EQ(jsonText(j, -1), "{\"file\":\"caf\xef\xbf\xbd.json\",\"name\":\"caf\xc3\xa9\"}");
  EXPECT_EQ(nlohmann::json::parse(jsonText(j)).at("name"), "caf\xc3\xa9");
}

}  // namespace
}  // namespace vcontact::io
