#pragma once
// User-written seams and tags that override or complete TAGCON's (`sartor
// construct|drape --seams-file`; docs/pattern-format.md#user-seams-and-tags).
// The file is the seam file of `sartor run` (docs/formats.md) with lines
// named by their pattern ids instead of mesh vertices, plus "tags" (panel or
// pack tags replacing the pattern's before construction), "unseam" (lines
// whose TAGCON seams are removed) and "replace_tagcon" (keep none of
// TAGCON's seams but the darts). Serial, no PETSc.

#include "garment/pattern.hpp"
#include "garment/tagcon.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sartor::garment {

struct UserSeam {
  std::string a, b;            // line ids; an interior line makes it a T-seam
  std::optional<bool> reverse; // unset: the orientation TAGCON would choose
  double certainty = 1.0;      // in (0, 1]
  std::string where;           // "FILE: seams[I] ('NAME')", for messages
};

struct SeamOverrides {
  std::string source;
  std::vector<std::pair<std::string, PanelTag>> tags; // panel or pack id, its new tag
  std::vector<std::string> unseam;                    // line ids
  std::vector<UserSeam> seams;
  bool replace_tagcon = false;
};

// A tag {"cylinder", "side", "layer"} as the pattern format writes it;
// throws InputError "WHERE: what is wrong".
PanelTag read_panel_tag(const nlohmann::json& value, const std::string& where);

// Throws InputError "FILE: PATH: what is wrong" for bad JSON, unknown keys,
// wrong types, vertex lists where line ids are expected, unknown tag names.
SeamOverrides parse_seam_overrides(const std::string& text, const std::string& source);
SeamOverrides read_seam_overrides(const std::string& path);

// Replaces the tags the file gives (a pack id retags all its panels). Throws
// InputError for an unknown panel or pack, or a pack left with mixed tags.
void apply_tag_overrides(Pattern& pattern, const SeamOverrides& overrides);

// Removes TAGCON's seams of every line the file names (in "seams" or
// "unseam"; all but the darts with "replace_tagcon") and adds the file's
// seams, kind `user`; updates the unseamed lines. Throws InputError for an
// unknown line, a dart's leg, a line sewn to itself or two interior lines.
void apply_seam_overrides(Construction& construction, const SeamOverrides& overrides);

} // namespace sartor::garment
