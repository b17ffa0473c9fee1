// Sloper parameters of the pattern format (docs/pattern-format.md#parameters):
// read and checked against the pattern's outline lines.

#include "common/csv.hpp"
#include "common/error.hpp"
#include "garment/pattern.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <map>
#include <set>

namespace sartor::garment {

namespace {

// A corner moved farther than this per metre of its parameter is a typo
// (a move given in cm per m, say), not a design.
constexpr double largest_per_unit = 10.0;

using Fail = std::function<void(const std::string&, const std::string&)>;

std::string key_list(std::initializer_list<const char*> keys) {
  std::string list;
  for (const char* key : keys)
    list += std::string(list.empty() ? "" : ", ") + key;
  return list;
}

void only_keys(const nlohmann::json& item, const std::string& where,
               std::initializer_list<const char*> keys, const Fail& fail) {
  for (const auto& entry : item.items()) {
    bool known = false;
    for (const char* key : keys)
      known = known || entry.key() == key;
    if (!known)
      fail(where, "unknown key '" + entry.key() + "' (expected one of: " + key_list(keys) + ")");
  }
}

ParameterMove read_move(const nlohmann::json& item, const std::string& where,
                        const Pattern& pattern, const Fail& fail) {
  if (!item.is_object()) fail(where, "expected an object {\"line\": ..., \"per_unit\": [dx, dy]}");
  only_keys(item, where, {"line", "corner", "per_unit"}, fail);
  ParameterMove move;
  if (!item.contains("line") || !item["line"].is_string())
    fail(where, "a move needs the string 'line' (an outline line of the pattern)");
  move.line = item["line"].get<std::string>();
  if (moved_outline_points(pattern, move.line, LineCorners::both).empty())
    fail(where + ".line", "'" + move.line + "' is not an outline line of the pattern");
  if (item.contains("corner")) {
    const std::string corner = item["corner"].is_string() ? item["corner"].get<std::string>() : "";
    if (corner == "start")
      move.corner = ParameterMove::Corner::start;
    else if (corner == "end")
      move.corner = ParameterMove::Corner::end;
    else
      fail(where + ".corner", "expected \"start\" or \"end\" (without it, both corners move)");
  }
  const auto per_unit = item.find("per_unit");
  if (per_unit == item.end() || !per_unit->is_array() || per_unit->size() != 2 ||
      !(*per_unit)[0].is_number() || !(*per_unit)[1].is_number())
    fail(where + ".per_unit", "expected two numbers [dx, dy]: the corners' move per metre of "
                              "the parameter");
  move.per_unit = {(*per_unit)[0].get<double>(), (*per_unit)[1].get<double>()};
  if (!(move.per_unit.lpNorm<Eigen::Infinity>() <= largest_per_unit))
    fail(where + ".per_unit", "a move of " + format_number(move.per_unit.norm()) +
                                  " m per m: at most " + format_number(largest_per_unit));
  return move;
}

SloperParameter read_parameter(const nlohmann::json& item, const std::string& where,
                               const Pattern& pattern, const Fail& fail) {
  if (!item.is_object()) fail(where, "expected an object {\"id\": ..., \"moves\": [...]}");
  only_keys(item, where, {"id", "description", "moves"}, fail);
  SloperParameter parameter;
  parameter.json_path = where;
  if (!item.contains("id") || !item["id"].is_string() || item["id"].get<std::string>().empty())
    fail(where, "a parameter needs a non-empty string 'id'");
  parameter.id = item["id"].get<std::string>();
  if (item.contains("description")) {
    if (!item["description"].is_string()) fail(where + ".description", "expected a string");
    parameter.description = item["description"].get<std::string>();
  }
  const auto moves = item.find("moves");
  if (moves == item.end() || !moves->is_array() || moves->empty())
    fail(where + ".moves", "expected a non-empty array of moves");
  std::map<OutlinePoint, Eigen::Vector2d> moved;
  for (std::size_t m = 0; m < moves->size(); ++m) {
    const std::string move_where = where + ".moves[" + std::to_string(m) + "]";
    const ParameterMove& move =
        parameter.moves.emplace_back(read_move((*moves)[m], move_where, pattern, fail));
    for (const auto& corner : moved_outline_points(pattern, move.line, move.corner)) {
      const auto [entry, fresh] = moved.emplace(corner, move.per_unit);
      if (!fresh && entry->second != move.per_unit)
        fail(move_where, "moves the corner it shares with an earlier move of this parameter "
                         "differently");
    }
  }
  return parameter;
}

} // namespace

std::vector<OutlinePoint> moved_outline_points(const Pattern& pattern, const std::string& line,
                                               LineCorners corners, int control) {
  std::vector<OutlinePoint> points;
  for (std::size_t panel = 0; panel < pattern.panels.size(); ++panel) {
    const auto& outline = pattern.panels[panel].outline;
    for (std::size_t i = 0; i < outline.size(); ++i) {
      if (outline[i].id != line) continue;
      if (control > 0) {
        points.push_back({panel, i, control});
        continue;
      }
      if (corners != LineCorners::end) points.push_back({panel, i, 0});
      if (corners != LineCorners::start) points.push_back({panel, (i + 1) % outline.size(), 0});
    }
  }
  return points;
}

std::vector<SloperParameter> read_sloper_parameters(const nlohmann::json& parameters,
                                                    const std::string& path,
                                                    const std::string& source,
                                                    const Pattern& pattern) {
  const Fail fail = [&](const std::string& where, const std::string& message) {
    throw InputError(source + ": " + where + ": " + message);
  };
  if (!parameters.is_array())
    fail(path, "expected an array, got " + std::string(parameters.type_name()));
  std::vector<SloperParameter> result;
  std::set<std::string> ids;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const std::string where = path + "[" + std::to_string(k) + "]";
    result.push_back(read_parameter(parameters[k], where, pattern, fail));
    if (!ids.insert(result.back().id).second)
      fail(where + ".id", "duplicate parameter id '" + result.back().id + "'");
  }
  return result;
}

} // namespace sartor::garment
