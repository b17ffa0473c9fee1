// sartor import: a pattern from another program (DXF-AAMA, or an SVG drawn
// as FreeSewing draws) into Sartor's pattern JSON.

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "garment/import_dxf.hpp"
#include "garment/import_svg.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <filesystem>
#include <map>

namespace sartor {

const CommandSpec& import_command() {
  static const CommandSpec spec{
      "import",
      "import a pattern from DXF-AAMA or SVG (FreeSewing) into the pattern JSON",
      "sartor import FILE.dxf|FILE.svg [--tags TAGS.json] [--output PATTERN.json] "
      "[--units mm|cm|m|in] [--name TEXT]",
      "Reads the pieces of a DXF-AAMA file (ASTM D6673: a block per piece, boundary\n"
      "on layer 1 or sew line on layer 14, notches 4, mirror line 6, grain line 7,\n"
      "internal lines 8, \"Piece Name:\" and \"Quantity:\" texts) or an SVG as\n"
      "FreeSewing renders patterns (its own output, docs/freesewing.md: a group per\n"
      "part, the seam line a closed path of class \"fabric\", seam allowance \"sa\"\n"
      "ignored, grain line and cut-on-fold marks, notch <use> marks, mm) and writes\n"
      "them as a Sartor pattern (docs/patterns.md): a piece cut on the fold mirrored\n"
      "about it into one panel, a piece cut twice given a mirrored twin, the outline\n"
      "split into lines at corners and notches, V-shaped notches of two equal lines\n"
      "(straight or curved) declared as darts. The tag file gives each piece its\n"
      "TAGCON tag, fabric and cut, or leaves it out; pieces it does not name are\n"
      "(torso, front, 0). The pattern written is read back and validated.\n\n"
      "examples:\n"
      "  sartor import skirt.svg --tags skirt_tags.json --output skirt.json\n"
      "  sartor import cases/import/freesewing/penelope_cisFemaleAdult36.svg "
      "--tags cases/import/freesewing/penelope_tags.json\n"
      "  sartor import bodice.dxf --units mm --output bodice.json",
      {
          {"tags", "FILE", "",
           "tag file: tags, fabrics, cut counts per piece, pieces left out (JSON)"},
          {"output", "FILE", "out/import/pattern.json", "the pattern JSON written"},
          {"units", "UNIT", "", "DXF only: the drawing unit (mm, cm, m, in) [from the file]"},
          {"name", "TEXT", "", "the pattern's name [the input file's name]"},
      },
      1};
  return spec;
}

int run_import(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string path = invocation.command_line.positionals.at(0);
  const std::string output = options.text("output");
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  double unit = 0;
  if (options.is_set("units")) {
    static const std::map<std::string, double> units = {
        {"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}, {"in", 0.0254}};
    const auto found = units.find(options.text("units"));
    if (found == units.end())
      throw InputError("option --units: unknown unit '" + options.text("units") +
                       "' (expected mm, cm, m or in)");
    if (extension != ".dxf")
      throw InputError("option --units applies to DXF files; an SVG gives its units (width, "
                       "viewBox)");
    unit = found->second;
  }
  std::vector<garment::ImportedPiece> pieces;
  if (extension == ".dxf")
    pieces = garment::read_dxf_pieces(path, unit);
  else if (extension == ".svg")
    pieces = garment::read_svg_pieces(path);
  else
    throw InputError(path + ": unknown pattern file type '" + extension +
                     "' (expected .dxf or .svg)");
  garment::ImportSettings settings;
  if (options.is_set("tags")) settings = garment::read_import_settings(options.text("tags"));
  garment::ImportReport report;
  const std::string name = options.is_set("name") ? options.text("name")
                                                  : std::filesystem::path(path).filename().string();
  const nlohmann::json pattern = garment::imported_pattern(pieces, settings, name, &report);
  if (is_root()) {
    const auto folder = std::filesystem::path(output).parent_path();
    if (!folder.empty()) make_output_directory(folder.string());
    write_json(output, pattern);
  }
  SartorPetscCall(MPI_Barrier(PETSC_COMM_WORLD));
  const garment::Pattern read_back = garment::read_pattern(output);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %zu pieces\n", path.c_str(), pieces.size()));
  for (const std::string& line : report.lines)
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s\n", line.c_str()));
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "wrote %s: %zu panels in %zu packs, valid\n",
                              output.c_str(), read_back.panels.size(), read_back.packs.size()));
  return 0;
}

} // namespace sartor
