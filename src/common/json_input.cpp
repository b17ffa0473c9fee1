#include "common/json_input.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <set>
#include <vector>

namespace sartor {

namespace {

// A SAX pass that only looks for a key given twice in one object (nlohmann's
// DOM parser keeps the last silently, and its callback parser is quadratic
// in the length of an array). Syntax errors are left to the parse proper.
class DuplicateKeyFinder : public nlohmann::json_sax<nlohmann::json> {
public:
  bool found = false;
  std::string duplicate;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    open_objects_.emplace_back();
    return true;
  }
  bool key(string_t& name) override {
    if (open_objects_.back().insert(name).second) return true;
    found = true;
    duplicate = name;
    return false;
  }
  bool end_object() override {
    open_objects_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

private:
  std::vector<std::set<std::string>> open_objects_; // the keys of each open object
};

} // namespace

nlohmann::json parse_json_input(const std::string& text, const std::string& source) {
  using json = nlohmann::json;
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& error) {
    std::string message = error.what();
    // "[json.exception.parse_error.101] parse error at line 3, ...": without the tag.
    const std::size_t tag_end = message.find("] ");
    if (message.rfind("[json.exception.", 0) == 0 && tag_end != std::string::npos) {
      message.erase(0, tag_end + 2);
    }
    throw InputError(source + ": not valid JSON: " + message);
  }
  DuplicateKeyFinder finder;
  json::sax_parse(text, &finder);
  if (finder.found) {
    throw InputError(source + ": key \"" + finder.duplicate + "\" is given twice in one object");
  }
  return document;
}

} // namespace sartor
