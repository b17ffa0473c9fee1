// sartor pattern: read and validate a pattern, draw it, mesh its panels.

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/json_input.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "garment/dart_insertion.hpp"
#include "garment/pattern.hpp"
#include "garment/pattern_svg.hpp"
#include "mesh/obj.hpp"
#include "mesh/panel_mesher.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace sartor {

const CommandSpec& pattern_command() {
  static const CommandSpec spec{
      "pattern",
      "validate a sewing pattern (JSON), draw it as SVG, mesh its panels",
      "sartor pattern PATTERN.json [--output DIR] [--edge-length M] [--min-angle DEG] "
      "[--no-mesh] [--add-dart LINE:AT:WIDTH:DEPTH[:ID]]",
      "Reads a pattern in the JSON format of docs/pattern-format.md: panels with\n"
      "closed outlines of lines (straight, cubic Bezier, polyline), interior fold\n"
      "and T-seam lines, a grain line, a fabric and a TAGCON tag (cylinder, side,\n"
      "layer) each, and packs of panels arranged in 2D (thesis ch. 3). Checks it\n"
      "(every problem is reported with the file and the JSON path, e.g.\n"
      "panels[2].outline[3]), then triangulates every panel by constrained Delaunay\n"
      "refinement (CGAL) to the edge length and minimum angle asked for. Every\n"
      "outline line is first split into equal arc-length pieces of at most the edge\n"
      "length / sqrt(2), so that lines to be sewn together can be discretised alike\n"
      "(lines.json lists the vertices along every line).\n"
      "Material (u, v) coordinates follow the grain line (u along the warp).\n\n"
      "Output in DIR: pattern.svg (the panels as laid out), panel_ID.obj per panel\n"
      "(panel coordinates, z = 0, vt = material uv in m), pattern.obj (all panels\n"
      "as laid out in the SVG), lines.json (per line: its panel and the mesh\n"
      "vertices along it, in order), summary.json (triangles, angles, areas,\n"
      "meshing times).\n\n"
      "With --add-dart, a dart is added first (docs/pattern-format.md#adding-a-dart):\n"
      "the outline line LINE is cut WIDTH m wide around AT (the fraction of its arc\n"
      "length) and a V reaching DEPTH m into the panel is sewn there; the pattern\n"
      "with the dart is written to DIR/pattern.json and is what the rest checks,\n"
      "draws and meshes. Drape it from the drape of the pattern without it with\n"
      "sartor drape DIR/pattern.json --start-from DRAPE_DIR.\n\n"
      "examples:\n"
      "  sartor pattern cases/patterns/skirt.json --output out/skirt\n"
      "  sartor pattern cases/patterns/tshirt.json --edge-length 0.01 --min-angle 30\n"
      "  sartor pattern cases/patterns/skirt.json --add-dart sf_waist_r:0.5:0.03:0.1",
      {
          {"output", "DIR", "out/pattern", "output folder (created; files in it are replaced)"},
          {"edge-length", "M", "0.02", "target (longest) triangle edge length, m"},
          {"min-angle", "DEG", "25", "smallest triangle angle, degrees, in (0, 33]"},
          {"no-mesh", "", "", "validate and draw only"},
          {"add-dart", "LINE:AT:WIDTH:DEPTH[:ID]", "",
           "add a dart on outline line LINE, its middle at the fraction AT of the line's arc "
           "length, WIDTH m wide, DEPTH m deep (id ID, or LINE_dart); writes DIR/pattern.json"},
      },
      1};
  return spec;
}

namespace {

// Panel ids are free text; file names keep to a portable set.
std::string file_name_of(const std::string& id) {
  std::string name;
  for (char c : id)
    name += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return "panel_" + name + ".obj";
}

// A panel's entry in summary.json, before meshing.
nlohmann::json panel_json(const garment::Pattern& pattern, std::size_t i, double tolerance) {
  const garment::Panel& panel = pattern.panels[i];
  return {{"id", panel.id},
          {"tag",
           {{"cylinder", garment::name_of(panel.tag.cylinder)},
            {"side", garment::name_of(panel.tag.side)},
            {"layer", panel.tag.layer}}},
          {"fabric", panel.fabric},
          {"pack", pattern.packs[pattern.pack_of(int(i))].id},
          {"outline_given_clockwise", panel.reversed},
          {"outline_area_m2", panel.area(tolerance)}};
}

// Appends a panel's mesh, laid out by `placement`, to `combined`; the
// offset of its vertices there.
int append_laid_out(const TriangleMesh& mesh, const garment::Placement& placement,
                    TriangleMesh* combined) {
  const int offset = int(combined->vertex_count());
  for (const auto& p : mesh.positions) {
    const Eigen::Vector2d placed = placement.apply(p.head<2>());
    combined->positions.emplace_back(placed.x(), placed.y(), 0.0);
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& triangle = mesh.triangles[t];
    combined->triangles.push_back(
        {triangle[0] + offset, triangle[1] + offset, triangle[2] + offset});
    combined->material_uv.push_back(mesh.material_uv[t]);
  }
  return offset;
}

// A meshed line's entry in lines.json (its vertices in the panel's mesh and,
// offset, in pattern.obj); warns when the mesher split it.
nlohmann::json line_json(const garment::Panel& panel, const MeshedLine& line, int offset) {
  nlohmann::json pattern_vertices = nlohmann::json::array();
  for (int v : line.vertices)
    pattern_vertices.push_back(v + offset);
  std::string kind = "outline";
  double length = 0;
  bool y_seam = false;
  for (const auto& outline : panel.outline) {
    if (outline.id == line.id) {
      length = outline.curve.length();
      y_seam = outline.y_seam;
    }
  }
  for (const auto& interior : panel.interior) {
    if (interior.id == line.id) {
      kind = garment::name_of(interior.kind);
      length = interior.curve.length();
    }
  }
  if (line.split_by_mesher) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "warning: the mesher split line '%s' of panel '%s' beyond "
                                "its %d pieces\n",
                                line.id.c_str(), panel.id.c_str(), line.pieces));
  }
  return {{"id", line.id},
          {"panel", panel.id},
          {"kind", kind},
          {"y_seam", y_seam},
          {"length_m", length},
          {"pieces", line.pieces},
          {"forced", line.forced},
          {"split_by_mesher", line.split_by_mesher},
          {"vertices", line.vertices},
          {"pattern_vertices", pattern_vertices}};
}

// What meshing a panel gave, into its summary entry.
void add_mesh_json(const PanelMesh& result, const std::string& file, double seconds,
                   nlohmann::json& entry) {
  entry["obj"] = file;
  entry["vertices"] = result.mesh.vertex_count();
  entry["triangles"] = result.mesh.triangle_count();
  entry["min_angle_deg"] = result.min_angle_deg;
  entry["min_angle_regular_deg"] = result.min_angle_regular_deg;
  entry["mesh_area_m2"] = result.area;
  entry["boundary_polygon_area_m2"] = result.boundary_area;
  entry["meshing_rounds"] = result.rounds;
  entry["mesh_seconds"] = seconds;
}

nlohmann::json packs_json(const garment::Pattern& pattern) {
  nlohmann::json packs = nlohmann::json::array();
  for (const auto& pack : pattern.packs) {
    nlohmann::json members = nlohmann::json::array();
    for (const auto& member : pack.members)
      members.push_back(pattern.panels[member.panel].id);
    packs.push_back({{"id", pack.id}, {"implicit", pack.implicit}, {"panels", members}});
  }
  return packs;
}

// --add-dart LINE:AT:WIDTH:DEPTH[:ID].
garment::DartInsertion dart_option(const std::string& text) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t colon; (colon = text.find(':', start)) != std::string::npos; start = colon + 1)
    fields.push_back(text.substr(start, colon - start));
  fields.push_back(text.substr(start));
  const auto fail = [&](const std::string& what) {
    throw InputError("option --add-dart: '" + text + "': " + what +
                     " (expected LINE:AT:WIDTH:DEPTH[:ID], e.g. sf_waist_r:0.5:0.03:0.1)");
  };
  if (fields.size() != 4 && fields.size() != 5) fail("four or five fields separated by ':'");
  garment::DartInsertion dart;
  dart.line = fields[0];
  const std::array<double*, 3> numbers{&dart.at, &dart.width, &dart.depth};
  for (std::size_t k = 0; k < 3; ++k) {
    char* end = nullptr;
    *numbers[k] = std::strtod(fields[k + 1].c_str(), &end);
    if (fields[k + 1].empty() || *end != '\0' || !std::isfinite(*numbers[k]))
      fail("'" + fields[k + 1] + "' is not a number");
  }
  if (fields.size() == 5) dart.id = fields[4];
  return dart;
}

// The pattern file with the dart of --add-dart, written to
// DIRECTORY/pattern.json; its path.
std::string add_dart_to_pattern(const std::string& path, const std::string& option,
                                const std::string& directory) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the pattern file");
  std::ostringstream text;
  text << in.rdbuf();
  const garment::DartInsertion dart = dart_option(option);
  const nlohmann::json with_dart =
      garment::add_dart(parse_json_input(text.str(), path), path, dart);
  const std::string written = directory + "/pattern.json";
  if (is_root()) {
    make_output_directory(directory);
    write_json(written, with_dart);
  }
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: added dart '%s' on line '%s': wrote %s\n",
                              path.c_str(),
                              (dart.id.empty() ? dart.line + "_dart" : dart.id).c_str(),
                              dart.line.c_str(), written.c_str()));
  return written;
}

} // namespace

int run_pattern(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string directory = options.text("output");
  const std::string path = options.is_set("add-dart")
                               ? add_dart_to_pattern(invocation.command_line.positionals.at(0),
                                                     options.text("add-dart"), directory)
                               : invocation.command_line.positionals.at(0);
  const bool mesh = !options.flag("no-mesh");
  PanelMeshOptions mesh_options;
  mesh_options.edge_length = options.positive_real("edge-length");
  mesh_options.min_angle_deg = options.positive_real("min-angle");
  if (mesh_options.min_angle_deg > 33)
    throw InputError("option --min-angle: must be <= 33 degrees, got " + options.text("min-angle"));

  const garment::Pattern pattern = garment::read_pattern(path);
  if (mesh) check_panel_mesh_size(pattern, mesh_options.edge_length);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %zu panels in %zu packs, valid\n",
                              path.c_str(), pattern.panels.size(), pattern.packs.size()));
  if (is_root()) {
    make_output_directory(directory);
    garment::write_pattern_svg(directory + "/pattern.svg", pattern);
  }

  const double tolerance = pattern.flattening_tolerance();
  nlohmann::json summary = run_metadata(invocation, "pattern");
  summary["pattern"] = path;
  summary["units"] = "m";
  nlohmann::json panels = nlohmann::json::array();
  nlohmann::json lines = nlohmann::json::array();
  TriangleMesh combined;
  const auto layout = garment::sheet_layout(pattern, 0.05);
  std::size_t total_triangles = 0;
  double worst_angle = 180, worst_regular_angle = 180;

  if (mesh) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-16s %-22s %9s %9s %9s %11s %9s\n", "panel",
                                "tag", "vertices", "triangles", "min angle", "area (m^2)",
                                "time (s)"));
  }
  for (std::size_t i = 0; i < pattern.panels.size(); ++i) {
    const garment::Panel& panel = pattern.panels[i];
    nlohmann::json entry = panel_json(pattern, i, tolerance);
    if (!mesh) {
      panels.push_back(entry);
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const PanelMesh result = mesh_panel(panel, mesh_options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string file = file_name_of(panel.id);
    if (is_root()) write_obj(directory + "/" + file, result.mesh);

    const int offset = append_laid_out(result.mesh, layout[i], &combined);
    for (const MeshedLine& line : result.lines)
      lines.push_back(line_json(panel, line, offset));
    total_triangles += result.mesh.triangle_count();
    worst_angle = std::min(worst_angle, result.min_angle_deg);
    worst_regular_angle = std::min(worst_regular_angle, result.min_angle_regular_deg);
    add_mesh_json(result, file, seconds, entry);
    panels.push_back(entry);
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-16s %-22s %9zu %9zu %9.2f %11.5f %9.3f\n",
                                panel.id.c_str(), garment::to_string(panel.tag).c_str(),
                                result.mesh.vertex_count(), result.mesh.triangle_count(),
                                result.min_angle_deg, result.area, seconds));
  }

  summary["panels"] = panels;
  summary["packs"] = packs_json(pattern);
  if (mesh) {
    summary["edge_length_m"] = mesh_options.edge_length;
    summary["requested_min_angle_deg"] = mesh_options.min_angle_deg;
    summary["triangles"] = total_triangles;
    summary["min_angle_deg"] = worst_angle;
    summary["min_angle_regular_deg"] = worst_regular_angle;
    if (is_root()) {
      write_obj(directory + "/pattern.obj", combined);
      write_json(directory + "/lines.json", {{"pattern", path}, {"lines", lines}});
    }
  }
  if (is_root()) write_json(directory + "/summary.json", summary);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "wrote %s\n", directory.c_str()));
  return 0;
}

} // namespace sartor
