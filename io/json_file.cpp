#include "io/json_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <vector>

#include "geometry/error.hpp"
#include "io/output_file.hpp"

namespace vcontact::io {
namespace {

/// Where the parser is in the document, as a key path ("bodies[1].pose"), and the keys each
/// open object has had so far. JSON allows a repeated key and nlohmann keeps the last one
/// silently (a scenario's second "duration" won); a file with one is refused instead, and so is
/// a number beyond the range of a double (1e400 would be read as infinity).
class StrictReader {
 public:
  explicit StrictReader(std::string path) : path_(std::move(path)) {}

  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        countElement();
        stack_.push_back(Frame{event == Event::object_start, {}, {}, -1});
        break;
      case Event::object_end:
      case Event::array_end:
        stack_.pop_back();
        break;
      case Event::key:
        takeKey(parsed.get<std::string>());
        break;
      case Event::value:
        countElement();
        if (parsed.is_number_float() && !std::isfinite(parsed.get<double>())) {
          fail("a number beyond the range of a double (about ±1.8e308 at most)");
        }
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;  ///< the latest key of an object
    int index;        ///< the latest element of an array
  };

  void countElement() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
  }

  void takeKey(const std::string& key) {
    Frame& f = stack_.back();
    f.key = key;
    if (!f.keys.insert(key).second) {
      fail(
          "the key appears twice in one object; JSON readers would keep only the last one, "
          "so say it once");
    }
  }

  /// The key path of the latest value; with `next`, of the value being read (an array's
  /// element not yet counted: the parser stops inside it).
  std::string where(bool next = false) const {
    std::string at;
    for (const Frame& f : stack_) {
      if (f.object && !f.key.empty()) {
        if (!at.empty()) at += '.';
        at += f.key;
      }
      const int index = f.index + (next && &f == &stack_.back() ? 1 : 0);
      if (!f.object && index >= 0) {
        at += '[';
        at += std::to_string(index);
        at += ']';
      }
    }
    return at.empty() ? "top level" : at;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, where() + ": " + what);
  }

 public:
  /// nlohmann refuses a number beyond a double itself (out_of_range 406), inside the value.
  [[noreturn]] void overflow(const std::string& text) const {
    throw InputError(path_, where(true) + ": a number beyond the range of a double (" + text +
                                ", about ±1.8e308 at most)");
  }

 private:
  std::string path_;
  std::vector<Frame> stack_;
};

// `input`: a stream or a string.
template <typename Input>
nlohmann::json parseStrictly(Input&& input, const std::string& source) {
  StrictReader reader(source);
  try {
    return nlohmann::json::parse(std::forward<Input>(input), std::ref(reader));
  } catch (const nlohmann::json::parse_error& e) {
    std::ostringstream os;
    os << "not valid JSON (byte " << e.byte << "): " << e.what();
    throw InputError(source, os.str());
  } catch (const nlohmann::json::out_of_range& e) {
    const std::string what = e.what();  // "... number overflow parsing '1e400'"
    const auto open = what.find('\'');
    reader.overflow(open == std::string::npos ? "?" : what.substr(open));
  }
}

}  // namespace

nlohmann::json readJsonFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path, "is a folder; expected a JSON file");
  }
  std::ifstream in(path);
  if (!in) {
    throw InputError(path, std::filesystem::exists(path, ec) ? "cannot be read" : "no such file");
  }
  return parseStrictly(in, path);
}

nlohmann::json parseJsonText(const std::string& text, const std::string& source) {
  return parseStrictly(text, source);
}

std::string jsonText(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

void putJson(const nlohmann::json& j, std::ostream& out) { out << jsonText(j) << '\n'; }

void writeJson(const nlohmann::json& j, const std::string& path) {
  const std::string text = jsonText(j) + '\n';  // dumped first: nothing opened for a bad value
  writeFile(path, [&](std::ostream& out) { out << text; });
}

}  // namespace vcontact::io
