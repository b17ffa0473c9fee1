// Darts of the pattern format (docs/pattern-format.md#darts): read and
// checked against the panel's outline once it is counter-clockwise.

#include "common/csv.hpp"
#include "common/error.hpp"
#include "garment/pattern.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace sartor::garment {

namespace {

// Legs of one dart may differ this much in length (relative to the longer):
// a tailor trues a dart's legs to equal length; more than this is a drafting
// error the seam would have to ease in.
constexpr double leg_length_mismatch = 0.05;

int outline_index(const Panel& panel, const std::string& id) {
  for (std::size_t i = 0; i < panel.outline.size(); ++i)
    if (panel.outline[i].id == id) return int(i);
  return -1;
}

// The direction in which a curve leaves its start (at_end false) or
// arrives at its end (at_end true).
Eigen::Vector2d tangent(const Curve& curve, bool at_end) {
  const auto points = curve.flatten(1e-9 * std::max(1e-3, curve.length()));
  return at_end ? Eigen::Vector2d(points.back() - points[points.size() - 2])
                : Eigen::Vector2d(points[1] - points.front());
}

} // namespace

std::vector<Dart> read_darts(const nlohmann::json& darts, const std::string& path,
                             const std::string& source, const Panel& panel) {
  const auto fail = [&](const std::string& where, const std::string& message) {
    throw InputError(source + ": " + where + ": " + message);
  };
  if (!darts.is_array()) fail(path, "expected an array, got " + std::string(darts.type_name()));
  std::vector<Dart> result;
  std::set<std::string> ids, legs_taken;
  for (std::size_t k = 0; k < darts.size(); ++k) {
    const std::string where = path + "[" + std::to_string(k) + "]";
    const nlohmann::json& item = darts[k];
    if (!item.is_object()) fail(where, "expected an object {\"id\": ..., \"legs\": [A, B]}");
    for (const auto& entry : item.items())
      if (entry.key() != "id" && entry.key() != "legs")
        fail(where, "unknown key '" + entry.key() + "' (expected one of: id, legs)");
    if (!item.contains("id") || !item["id"].is_string() || item["id"].get<std::string>().empty())
      fail(where, "a dart needs a non-empty string 'id'");
    Dart dart;
    dart.id = item["id"].get<std::string>();
    dart.json_path = where;
    if (!ids.insert(dart.id).second) fail(where, "duplicate dart id '" + dart.id + "'");
    const auto legs = item.find("legs");
    if (legs == item.end() || !legs->is_array() || legs->size() != 2 || !(*legs)[0].is_string() ||
        !(*legs)[1].is_string())
      fail(where, "'legs' must name two outline lines [\"A\", \"B\"]");
    int a = outline_index(panel, (*legs)[0].get<std::string>());
    int b = outline_index(panel, (*legs)[1].get<std::string>());
    for (const auto& [index, leg] : {std::pair{a, 0}, std::pair{b, 1}}) {
      if (index < 0)
        fail(where + ".legs[" + std::to_string(leg) + "]",
             "'" + (*legs)[std::size_t(leg)].get<std::string>() +
                 "' is not an outline line of panel '" + panel.id + "'");
    }
    const int n = int(panel.outline.size());
    if ((a + 1) % n != b) std::swap(a, b); // the file may list the legs either way round
    if ((a + 1) % n != b || a == b)
      fail(where, "the legs '" + panel.outline[std::size_t(a)].id + "' and '" +
                      panel.outline[std::size_t(b)].id +
                      "' are not consecutive lines of the outline (a dart's legs meet at its "
                      "apex)");
    const OutlineLine& first = panel.outline[std::size_t(a)];
    const OutlineLine& second = panel.outline[std::size_t(b)];
    for (const OutlineLine* leg : {&first, &second})
      if (!legs_taken.insert(leg->id).second)
        fail(where, "line '" + leg->id + "' is a leg of another dart too");
    const Eigen::Vector2d in = tangent(first.curve, true), out = tangent(second.curve, false);
    // Counter-clockwise outline: a V cut into the panel turns clockwise at its apex.
    if (in.x() * out.y() - in.y() * out.x() >= 0)
      fail(where, "the legs '" + first.id + "' and '" + second.id + "' meet at a convex corner " +
                      "(" + format_number(first.curve.end().x()) + ", " +
                      format_number(first.curve.end().y()) +
                      "): a dart is a V cut into the panel, its apex inside");
    const double la = first.curve.length(), lb = second.curve.length();
    if (std::abs(la - lb) > leg_length_mismatch * std::max(la, lb))
      fail(where, "the legs differ in length: '" + first.id + "' " + format_number(la) + " m, '" +
                      second.id + "' " + format_number(lb) +
                      " m (more than 5%; true the dart's legs)");
    dart.first_leg = first.id;
    dart.second_leg = second.id;
    result.push_back(dart);
  }
  return result;
}

} // namespace sartor::garment
