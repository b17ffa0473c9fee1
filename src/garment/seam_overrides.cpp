#include "garment/seam_overrides.hpp"

#include "common/error.hpp"
#include "common/json_input.hpp"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

namespace sartor::garment {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw InputError(where + ": " + message);
}

void only_keys(const json& object, const std::string& where,
               std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    if (std::none_of(allowed.begin(), allowed.end(),
                     [&](const char* name) { return item.key() == name; })) {
      std::string list;
      for (const char* name : allowed)
        list += std::string(list.empty() ? "" : ", ") + name;
      fail(where, "unknown key '" + item.key() + "' (expected one of: " + list + ")");
    }
  }
}

} // namespace

PanelTag read_panel_tag(const json& value, const std::string& where) {
  if (!value.is_object()) fail(where, "expected a tag {\"cylinder\", \"side\", \"layer\"}");
  only_keys(value, where, {"cylinder", "side", "layer"});
  PanelTag tag;
  if (!value.contains("cylinder") || !value["cylinder"].is_string())
    fail(where, "missing field 'cylinder' (a string)");
  const std::string alpha = value["cylinder"].get<std::string>();
  const auto& cylinders = all_cylinders();
  const auto found = std::find_if(cylinders.begin(), cylinders.end(),
                                  [&](Cylinder c) { return alpha == name_of(c); });
  if (found == cylinders.end()) {
    std::string list;
    for (Cylinder c : cylinders)
      list += std::string(list.empty() ? "" : ", ") + name_of(c);
    fail(where + ".cylinder", "unknown cylinder '" + alpha + "' (expected one of: " + list + ")");
  }
  tag.cylinder = *found;
  if (!value.contains("side") || !value["side"].is_string())
    fail(where, "missing field 'side' (front or back)");
  const std::string beta = value["side"].get<std::string>();
  if (beta != "front" && beta != "back")
    fail(where + ".side", "unknown side '" + beta + "' (expected front or back)");
  tag.side = beta == "front" ? Side::front : Side::back;
  if (value.contains("layer")) {
    if (!value["layer"].is_number_integer()) fail(where + ".layer", "expected an integer");
    tag.layer = value["layer"].get<int>();
  }
  return tag;
}

namespace {

std::string line_id(const json& value, const std::string& where) {
  if (value.is_array())
    fail(where, "names mesh vertices; the seams file of construct and drape names lines by "
                "their pattern ids (\"a\": \"front_side\")");
  if (!value.is_string() || value.get<std::string>().empty())
    fail(where, "expected a line id (a non-empty string)");
  return value.get<std::string>();
}

UserSeam read_seam(const json& value, const std::string& where) {
  if (!value.is_object()) fail(where, "expected an object {\"a\": LINE, \"b\": LINE}");
  only_keys(value, where, {"name", "a", "b", "reverse", "certainty"});
  UserSeam seam;
  seam.where = where;
  if (value.contains("name")) {
    if (!value["name"].is_string()) fail(where + ".name", "expected a string");
    seam.where += " ('" + value["name"].get<std::string>() + "')";
  }
  if (!value.contains("a") || !value.contains("b"))
    fail(seam.where, "needs both lines 'a' and 'b'");
  seam.a = line_id(value["a"], seam.where + ".a");
  seam.b = line_id(value["b"], seam.where + ".b");
  if (value.contains("reverse")) {
    if (!value["reverse"].is_boolean()) fail(where + ".reverse", "must be true or false");
    seam.reverse = value["reverse"].get<bool>();
  }
  if (value.contains("certainty")) {
    const json& c = value["certainty"];
    if (!c.is_number() || !(c.get<double>() > 0 && c.get<double>() <= 1))
      fail(where + ".certainty", "must be a number in (0, 1]");
    seam.certainty = c.get<double>();
  }
  return seam;
}

} // namespace

SeamOverrides parse_seam_overrides(const std::string& text, const std::string& source) {
  const json document = parse_json_input(text, source);
  if (!document.is_object()) fail(source, "expected a JSON object");
  only_keys(document, source, {"seams", "tags", "unseam", "replace_tagcon"});
  SeamOverrides overrides;
  overrides.source = source;
  if (document.contains("seams")) {
    const json& seams = document["seams"];
    if (!seams.is_array()) fail(source + ": seams", "expected an array");
    for (std::size_t k = 0; k < seams.size(); ++k)
      overrides.seams.push_back(read_seam(seams[k], source + ": seams[" + std::to_string(k) + "]"));
  }
  if (document.contains("tags")) {
    const json& tags = document["tags"];
    if (!tags.is_object()) fail(source + ": tags", "expected an object {PANEL_OR_PACK: TAG}");
    for (const auto& item : tags.items())
      overrides.tags.emplace_back(item.key(),
                                  read_panel_tag(item.value(), source + ": tags." + item.key()));
  }
  if (document.contains("unseam")) {
    const json& unseam = document["unseam"];
    if (!unseam.is_array()) fail(source + ": unseam", "expected an array of line ids");
    for (std::size_t k = 0; k < unseam.size(); ++k)
      overrides.unseam.push_back(
          line_id(unseam[k], source + ": unseam[" + std::to_string(k) + "]"));
  }
  if (document.contains("replace_tagcon")) {
    if (!document["replace_tagcon"].is_boolean())
      fail(source + ": replace_tagcon", "must be true or false");
    overrides.replace_tagcon = document["replace_tagcon"].get<bool>();
  }
  return overrides;
}

SeamOverrides read_seam_overrides(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the seams file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_seam_overrides(text.str(), path);
}

void apply_tag_overrides(Pattern& pattern, const SeamOverrides& overrides) {
  for (const auto& [id, tag] : overrides.tags) {
    const auto pack = std::find_if(pattern.packs.begin(), pattern.packs.end(),
                                   [&](const Pack& p) { return p.id == id && !p.implicit; });
    if (pack != pattern.packs.end()) {
      for (const auto& member : pack->members)
        pattern.panels[std::size_t(member.panel)].tag = tag;
      continue;
    }
    const auto panel = std::find_if(pattern.panels.begin(), pattern.panels.end(),
                                    [&](const Panel& p) { return p.id == id; });
    if (panel == pattern.panels.end())
      fail(overrides.source + ": tags." + id, "no panel or pack '" + id + "' in " + pattern.source);
    panel->tag = tag;
  }
  for (const Pack& pack : pattern.packs) {
    const Panel& first = pattern.panels[std::size_t(pack.members.front().panel)];
    for (const auto& member : pack.members) {
      const Panel& panel = pattern.panels[std::size_t(member.panel)];
      if (panel.tag != first.tag)
        fail(overrides.source + ": tags", "pack '" + pack.id + "' now mixes tags: panel '" +
                                              panel.id + "' is " + to_string(panel.tag) +
                                              " but panel '" + first.id + "' is " +
                                              to_string(first.tag) + " (retag the pack by its id)");
    }
  }
}

void apply_seam_overrides(Construction& construction, const SeamOverrides& overrides) {
  const auto index_of = [&](const std::string& id, const std::string& where) {
    const int index = construction.line_index(id);
    if (index < 0) fail(where, "no line '" + id + "' in " + construction.pattern->source);
    return index;
  };
  std::set<int> dart_legs;
  for (const FoundSeam& seam : construction.seams)
    if (seam.kind == SeamKind::dart) dart_legs.insert({seam.line_a, seam.line_b});
  std::set<int> released; // lines whose TAGCON seams go
  for (std::size_t k = 0; k < overrides.unseam.size(); ++k) {
    const std::string where = overrides.source + ": unseam[" + std::to_string(k) + "]";
    const int line = index_of(overrides.unseam[k], where);
    if (dart_legs.count(line)) fail(where, "'" + overrides.unseam[k] + "' is a dart's leg");
    released.insert(line);
  }
  std::vector<FoundSeam> added;
  for (const UserSeam& user : overrides.seams) {
    FoundSeam seam;
    seam.kind = SeamKind::user;
    seam.line_a = index_of(user.a, user.where + ".a");
    seam.line_b = index_of(user.b, user.where + ".b");
    for (int line : {seam.line_a, seam.line_b})
      if (dart_legs.count(line))
        fail(user.where, "'" + construction.lines[std::size_t(line)].id +
                             "' is a dart's leg, sewn to its other leg");
    if (seam.line_a == seam.line_b) fail(user.where, "sews line '" + user.a + "' to itself");
    const LineGeometry& a = construction.lines[std::size_t(seam.line_a)];
    const LineGeometry& b = construction.lines[std::size_t(seam.line_b)];
    if (a.interior && b.interior)
      fail(user.where, "both lines are interior lines; a T-seam sews an outline line onto one");
    seam.reverse = user.reverse ? *user.reverse : should_reverse(a, b);
    seam.certainty = user.certainty;
    seam.score.distance = seam.score.orientation = seam.score.length = seam.score.curvature =
        seam.score.seamable = 1;
    released.insert({seam.line_a, seam.line_b});
    added.push_back(seam);
  }
  std::vector<FoundSeam> kept;
  for (const FoundSeam& seam : construction.seams) {
    const bool dart = seam.kind == SeamKind::dart;
    const bool named = released.count(seam.line_a) || released.count(seam.line_b);
    if (dart || (!overrides.replace_tagcon && !named)) kept.push_back(seam);
  }
  kept.insert(kept.end(), added.begin(), added.end());
  construction.seams = kept;

  std::vector<std::string> reason(construction.lines.size());
  for (const UnseamedLine& line : construction.unseamed)
    reason[std::size_t(line.line)] = line.reason;
  std::vector<bool> seamed(construction.lines.size(), false);
  for (const FoundSeam& seam : construction.seams)
    seamed[std::size_t(seam.line_a)] = seamed[std::size_t(seam.line_b)] = true;
  construction.unseamed.clear();
  for (std::size_t i = 0; i < construction.lines.size(); ++i) {
    if (seamed[i]) continue;
    construction.unseamed.push_back(
        {int(i), reason[i].empty() ? "its seam was removed by " + overrides.source : reason[i]});
  }
}

} // namespace sartor::garment
