// TAGCON construction on the built-in mannequin, shared by `sartor construct`
// and `sartor drape`.

#include "app/garment_construction.hpp"

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "fem/petsc_call.hpp"
#include "garment/pattern_svg.hpp"
#include "garment/seam_overrides.hpp"
#include "garment/tagcon_svg.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

namespace sartor {

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json tag_json(const garment::PanelTag& tag) {
  return {{"cylinder", garment::name_of(tag.cylinder)},
          {"side", garment::name_of(tag.side)},
          {"layer", tag.layer}};
}

} // namespace

const std::vector<OptionSpec>& panel_mesh_option_specs() {
  static const std::vector<OptionSpec> specs{
      {"edge-length", "M", "0.02", "target (longest) triangle edge length, m"},
      {"min-angle", "DEG", "25", "smallest triangle angle, degrees, in (0, 33]"},
      {"no-prefold", "", "",
       "start creased panels flat (their creases keep their rest angles): docs/pleats.md"},
  };
  return specs;
}

PanelMeshOptions panel_mesh_options(const Options& options) {
  PanelMeshOptions mesh_options;
  mesh_options.edge_length = options.positive_real("edge-length");
  mesh_options.min_angle_deg = options.positive_real("min-angle");
  if (mesh_options.min_angle_deg > 33)
    throw InputError("option --min-angle: must be <= 33 degrees, got " + options.text("min-angle"));
  return mesh_options;
}

OptionSpec seams_file_option_spec() {
  return {"seam-file",
          "FILE",
          "",
          "seams and tags that override or complete TAGCON's: JSON naming pattern lines "
          "(docs/pattern-format.md#user-seams-and-tags)",
          false,
          "seams-file"};
}

ConstructedGarment construct_garment(const std::string& path, const PanelMeshOptions& mesh_options,
                                     const std::string& seams_file, bool prefold,
                                     const std::string& body_spec, const std::string& where) {
  ConstructedGarment constructed;
  constructed.path = path;
  constructed.seams_file = seams_file;
  constructed.mesh_options = mesh_options;
  constructed.pattern = garment::read_pattern(path);
  std::optional<garment::SeamOverrides> overrides;
  if (!seams_file.empty()) {
    overrides = garment::read_seam_overrides(seams_file);
    garment::apply_tag_overrides(constructed.pattern, *overrides);
  }
  check_panel_mesh_size(constructed.pattern, mesh_options.edge_length);
  using Clock = std::chrono::steady_clock;
  const auto body_start = Clock::now();
  constructed.body =
      std::make_shared<const contact::GarmentBody>(contact::garment_body(body_spec, where));
  for (const std::string& note : constructed.body->notes)
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "body: %s\n", note.c_str()));
  const Mannequin& body = constructed.body->mannequin;
  // Shared with the construction, which places points later too (the
  // levels of a progressive drape mesh it again).
  const std::shared_ptr<const contact::Shape> shape = constructed.body->distance;
  constructed.body_seconds = std::chrono::duration<double>(Clock::now() - body_start).count();
  const garment::BodyDistance distance = [shape](const Eigen::Vector3d& p,
                                                 Eigen::Vector3d* gradient) {
    const contact::SurfaceQuery q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  constructed.construction =
      garment::construct(constructed.pattern, body, distance, constructed.tagcon);
  if (overrides) garment::apply_seam_overrides(constructed.construction, *overrides);
  const auto mesh_start = Clock::now();
  constructed.garment =
      garment::build_garment_mesh(constructed.construction, mesh_options, prefold);
  constructed.mesh_seconds = std::chrono::duration<double>(Clock::now() - mesh_start).count();
  return constructed;
}

void print_construction(const ConstructedGarment& constructed) {
  const garment::Pattern& pattern = constructed.pattern;
  const garment::Construction& construction = constructed.construction;
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "%s: %zu panels in %zu packs; %zu seams, %zu lines unseamed; "
                              "construction %.4f s (placement %.4f s, seams %.4f s)\n",
                              constructed.path.c_str(), pattern.panels.size(), pattern.packs.size(),
                              construction.seams.size(), construction.unseamed.size(),
                              construction.placement_seconds + construction.seam_seconds,
                              construction.placement_seconds, construction.seam_seconds));
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-20s %-20s %-20s %9s\n", "kind", "line a",
                              "line b", "certainty"));
  for (const auto& seam : construction.seams) {
    SartorPetscCall(
        PetscPrintf(PETSC_COMM_WORLD, "%-20s %-20s %-20s %9.3f\n", garment::name_of(seam.kind),
                    construction.lines[std::size_t(seam.line_a)].id.c_str(),
                    construction.lines[std::size_t(seam.line_b)].id.c_str(), seam.certainty));
  }
}

namespace {

nlohmann::json tagcon_json(const garment::TagconOptions& tagcon) {
  return {{"clearance_m", tagcon.clearance},
          {"layer_gap_m", tagcon.layer_gap},
          {"lid_depth_m", tagcon.lid_depth},
          {"max_widening", tagcon.max_widening},
          {"fov_half_angle_deg", tagcon.fov_half_angle_deg},
          {"intra_distance_m", tagcon.intra_distance},
          {"d_max_m", tagcon.d_max},
          {"length_diff_m", tagcon.length_diff},
          {"curvature_diff_per_m", tagcon.curvature_diff},
          {"min_match", tagcon.min_match},
          {"clicks", tagcon.clicks},
          {"penetration_m", tagcon.penetration}};
}

nlohmann::json cylinders_json(const garment::Construction& construction) {
  nlohmann::json cylinders = nlohmann::json::array();
  for (const auto& c : construction.cylinders) {
    cylinders.push_back({{"cylinder", garment::name_of(c.cylinder)},
                         {"top", vector_json(c.top)},
                         {"up", vector_json(c.up)},
                         {"front", vector_json(c.front)},
                         {"length_m", c.length},
                         {"body_radius_m", c.body_radius},
                         {"radius_m", c.radius},
                         {"lid", c.lid},
                         {"anchor", c.anchor},
                         {"bones", c.bones}});
  }
  return cylinders;
}

// The packs as placed on their cylinders.
nlohmann::json placed_packs_json(const garment::Pattern& pattern,
                                 const garment::Construction& construction) {
  nlohmann::json packs = nlohmann::json::array();
  for (const auto& placed : construction.packs) {
    nlohmann::json members = nlohmann::json::array();
    for (const auto& member : pattern.packs[std::size_t(placed.pack)].members)
      members.push_back(pattern.panels[std::size_t(member.panel)].id);
    packs.push_back({{"id", pattern.packs[std::size_t(placed.pack)].id},
                     {"tag", tag_json(placed.tag)},
                     {"panels", members},
                     {"box_min", {placed.box_min.x(), placed.box_min.y()}},
                     {"box_max", {placed.box_max.x(), placed.box_max.y()}},
                     {"unrolled_offset", {placed.offset.x(), placed.offset.y()}},
                     {"radius_m", placed.radius}});
  }
  return packs;
}

nlohmann::json panels_json(const garment::Pattern& pattern, const garment::GarmentMesh& garment) {
  nlohmann::json panels = nlohmann::json::array();
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    panels.push_back({{"id", pattern.panels[p].id},
                      {"tag", tag_json(pattern.panels[p].tag)},
                      {"fabric", pattern.panels[p].fabric},
                      {"material_id", p},
                      {"first_vertex", garment.first_vertex[p]},
                      {"triangles", garment.triangle_count[p]}});
  }
  return panels;
}

nlohmann::json seams_json(const garment::Construction& construction,
                          const std::vector<garment::FoundSeam>& found) {
  nlohmann::json seams = nlohmann::json::array();
  for (const auto& seam : found) {
    seams.push_back({{"kind", garment::name_of(seam.kind)},
                     {"line_a", construction.lines[std::size_t(seam.line_a)].id},
                     {"line_b", construction.lines[std::size_t(seam.line_b)].id},
                     {"reverse", seam.reverse},
                     {"certainty", seam.certainty},
                     {"M",
                      {{"distance", seam.score.distance},
                       {"orientation", seam.score.orientation},
                       {"length", seam.score.length},
                       {"curvature", seam.score.curvature},
                       {"seamable", seam.score.seamable}}}});
  }
  return seams;
}

// Every line in 3D, with its mesh vertices and why it is unseamed, if it is.
nlohmann::json lines_json(const garment::Pattern& pattern,
                          const garment::Construction& construction,
                          const garment::GarmentMesh& garment) {
  nlohmann::json lines = nlohmann::json::array();
  std::vector<std::string> reason(construction.lines.size());
  for (const auto& u : construction.unseamed)
    reason[std::size_t(u.line)] = u.reason;
  for (std::size_t k = 0; k < construction.lines.size(); ++k) {
    const auto& line = construction.lines[k];
    nlohmann::json samples = nlohmann::json::array();
    for (const auto& p : line.samples)
      samples.push_back(vector_json(p));
    nlohmann::json entry = {{"id", line.id},
                            {"panel", pattern.panels[std::size_t(line.panel)].id},
                            {"interior", line.interior},
                            {"length_m", line.length},
                            {"curvature_per_m", line.curvature},
                            {"centre", vector_json(line.centre)},
                            {"normal", vector_json(line.normal)},
                            {"samples", samples},
                            {"vertices", garment.line_vertices.at(line.id)}};
    if (!reason[k].empty()) entry["unseamed"] = reason[k];
    lines.push_back(entry);
  }
  return lines;
}

nlohmann::json stitches_json(const garment::Pattern& pattern) {
  nlohmann::json stitches = nlohmann::json::array();
  for (const auto& stitch : pattern.stitches)
    stitches.push_back({{"line_a", stitch.line_a},
                        {"line_b", stitch.line_b},
                        {"reverse", stitch.reverse},
                        {"pleat", stitch.origin}});
  return stitches;
}

// Creased fold lines: their mesh vertices (garment.obj numbering), rest
// angle (element/bending.hpp's sign) and stiffness factor, for
// postproc/pleat_shape.py.
nlohmann::json creases_json(const garment::Pattern& pattern, const garment::GarmentMesh& garment) {
  std::map<std::pair<int, int>, double> rest_angles;
  for (const CreaseEdge& edge : garment.mesh.creases)
    rest_angles[std::minmax(edge.a, edge.b)] = edge.rest_angle;
  nlohmann::json creases = nlohmann::json::array();
  for (const auto& panel : pattern.panels) {
    for (const auto& line : panel.interior) {
      if (!line.crease) continue;
      const std::vector<int>& vertices = garment.line_vertices.at(line.id);
      creases.push_back({{"line", line.id},
                         {"panel", panel.id},
                         {"vertices", vertices},
                         {"angle_deg", line.crease->angle * 180.0 / M_PI},
                         {"toward", line.crease->outside ? "outside" : "inside"},
                         {"pressed", line.crease->pressed},
                         {"rest_angle_deg",
                          rest_angles.at(std::minmax(vertices[0], vertices[1])) * 180.0 / M_PI}});
    }
  }
  return creases;
}

} // namespace

nlohmann::json construction_summary(const Invocation& invocation, const std::string& command,
                                    const std::string& pattern_path,
                                    const ConstructedGarment& constructed) {
  nlohmann::json summary = run_metadata(invocation, command);
  summary["pattern"] = pattern_path;
  if (!constructed.seams_file.empty()) summary["seams_file"] = constructed.seams_file;
  summary["body"] = constructed.body->is_default ? "default" : constructed.body->source;
  summary["units"] = "m";
  const garment::Pattern& pattern = constructed.pattern;
  const PanelMeshOptions& mesh_options = constructed.mesh_options;
  const garment::Construction& construction = constructed.construction;
  const garment::GarmentMesh& garment = constructed.garment;
  summary["tagcon_options"] = tagcon_json(constructed.tagcon);
  summary["cylinders"] = cylinders_json(construction);
  summary["packs"] = placed_packs_json(pattern, construction);
  summary["panels"] = panels_json(pattern, garment);
  summary["seams"] = seams_json(construction, construction.seams);
  summary["deleted_seams"] = seams_json(construction, construction.deleted);
  summary["lines"] = lines_json(pattern, construction, garment);
  summary["stitches"] = stitches_json(pattern);
  summary["creases"] = creases_json(pattern, garment);
  summary["mesh"] = {{"vertices", garment.mesh.vertex_count()},
                     {"triangles", garment.mesh.triangle_count()},
                     {"edge_length_m", mesh_options.edge_length},
                     {"min_angle_deg", mesh_options.min_angle_deg}};
  summary["timings"] = {
      {"construction_seconds", construction.placement_seconds + construction.seam_seconds},
      {"placement_seconds", construction.placement_seconds},
      {"seam_seconds", construction.seam_seconds},
      {"body_setup_seconds", constructed.body_seconds},
      {"meshing_seconds", constructed.mesh_seconds}};
  return summary;
}

void write_construction(const std::string& directory, const ConstructedGarment& constructed,
                        const nlohmann::json& summary) {
  if (!is_root()) return;
  const garment::Pattern& pattern = constructed.pattern;
  const garment::Construction& construction = constructed.construction;
  const garment::GarmentMesh& garment = constructed.garment;
  const Mannequin& body = constructed.body->mannequin;
  make_output_directory(directory);
  garment::write_garment_obj(directory + "/garment.obj", garment, pattern);
  write_seams(directory + "/seams.json", garment.seams);
  write_json(directory + "/construct.json", summary);
  garment::SvgOptions svg;
  for (const auto& seam : construction.seams)
    svg.seams.push_back({construction.lines[std::size_t(seam.line_a)].id,
                         construction.lines[std::size_t(seam.line_b)].id, seam.certainty});
  garment::write_pattern_svg(directory + "/pattern_seams.svg", pattern, svg);
  write_file_atomically(directory + "/placement.svg",
                        garment::placement_svg(construction, body.mesh.vertices, body.mesh.faces));
}

} // namespace sartor
