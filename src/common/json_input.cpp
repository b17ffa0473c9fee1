#include "common/json_input.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <set>
#include <vector>

namespace sartor {

nlohmann::json parse_json_input(const std::string& text, const std::string& source) {
  using json = nlohmann::json;
  // The keys seen so far in each object being read, innermost last.
  std::vector<std::set<std::string>> open_objects;
  const json::parser_callback_t no_duplicate_keys = [&](int, json::parse_event_t event,
                                                        json& parsed) {
    if (event == json::parse_event_t::object_start) open_objects.emplace_back();
    if (event == json::parse_event_t::object_end) open_objects.pop_back();
    if (event == json::parse_event_t::key && !open_objects.back().insert(parsed).second) {
      const std::string key = parsed.get<std::string>();
      throw InputError(source + ": key \"" + key + "\" is given twice in one object");
    }
    return true;
  };
  try {
    return json::parse(text, no_duplicate_keys);
  } catch (const json::exception& error) {
    std::string message = error.what();
    // "[json.exception.parse_error.101] parse error at line 3, ...": without the tag.
    const std::size_t tag_end = message.find("] ");
    if (message.rfind("[json.exception.", 0) == 0 && tag_end != std::string::npos) {
      message.erase(0, tag_end + 2);
    }
    throw InputError(source + ": not valid JSON: " + message);
  }
}

} // namespace sartor
