// sartor construct: TAGCON garment construction (thesis ch. 3) from a tagged
// and packed pattern: positioned panels, seams, pictures.

#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/mesh_shape.hpp"
#include "fem/petsc_call.hpp"
#include "garment/garment_mesh.hpp"
#include "garment/pattern.hpp"
#include "garment/pattern_svg.hpp"
#include "garment/tagcon.hpp"
#include "garment/tagcon_svg.hpp"
#include "mesh/mannequin.hpp"
#include "solvers/commands.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <chrono>

namespace sartor {

const CommandSpec& construct_command() {
  static const CommandSpec spec{
      "construct",
      "TAGCON: place a tagged, packed pattern around the body and find its seams",
      "sartor construct PATTERN.json [--body default] [--output DIR] [--edge-length M] "
      "[--min-angle DEG]",
      "Constructs a garment from a pattern (docs/pattern-format.md) as the thesis'\n"
      "TAGCON does (ch. 3; docs/tagcon.md): cylinders fitted to the body's skeleton\n"
      "(torso, arms, legs, neck, head); each pack's bounding box wrapped onto its\n"
      "half cylinder (front or back), layers outside; then the seams: inter-layer\n"
      "(T- and Y-seams), intra-pack (closest line in the field of view), inter-\n"
      "cylinder (ring match with clicks) and inter-half-cylinder (greedy on the\n"
      "objective M(i, j) = M_ld M_lo M_ll M_lc M_sa, eqs. 3.1-3.6); seams whose sweep\n"
      "penetrates the body are deleted. Each seam carries its certainty M.\n"
      "A garment TAGCON cannot construct (a panel spanning two cylinders, thesis\n"
      "Fig. 3.9; a pack none of whose lines can be seamed) is an error that names\n"
      "the lines and the reason.\n\n"
      "Output in DIR: garment.obj (all panels meshed and placed; vt = material uv\n"
      "in m; g/usemtl per panel), seams.json (seam file for `sartor run\n"
      "--seams-file`, vertex numbers of garment.obj), construct.json (cylinders,\n"
      "pack placements, every line in 3D with its seam or the reason it has none,\n"
      "seams with kind, certainty and the five factors, timings), pattern_seams.svg\n"
      "(the pattern with its seams, blue = certain to red = uncertain),\n"
      "placement.svg (front and side views of the placed panels on the body).\n\n"
      "examples:\n"
      "  sartor construct cases/patterns/tshirt.json --output out/tshirt\n"
      "  sartor run --mesh obj --mesh-file out/tshirt/garment.obj \\\n"
      "      --seams-file out/tshirt/seams.json --body mannequin ...",
      {
          {"body", "NAME", "default", "the body: default (the built-in mannequin)"},
          {"output", "DIR", "out/construct", "output folder (created; files in it are replaced)"},
          {"edge-length", "M", "0.02", "target (longest) triangle edge length, m"},
          {"min-angle", "DEG", "25", "smallest triangle angle, degrees, in (0, 33]"},
      },
      1};
  return spec;
}

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

int run_construct(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string path = invocation.command_line.positionals.at(0);
  const std::string directory = options.text("output");
  if (options.text("body") != "default")
    throw InputError("option --body: unknown body '" + options.text("body") +
                     "' (expected: default, the built-in mannequin)");
  PanelMeshOptions mesh_options;
  mesh_options.edge_length = options.positive_real("edge-length");
  mesh_options.min_angle_deg = options.positive_real("min-angle");
  if (mesh_options.min_angle_deg > 33)
    throw InputError("option --min-angle: must be <= 33 degrees, got " + options.text("min-angle"));

  const garment::Pattern pattern = garment::read_pattern(path);
  using Clock = std::chrono::steady_clock;
  const auto body_start = Clock::now();
  const Mannequin& body = default_mannequin();
  const auto shape = contact::make_mannequin_shape();
  const double body_seconds = std::chrono::duration<double>(Clock::now() - body_start).count();
  const garment::BodyDistance distance = [&shape](const Eigen::Vector3d& p,
                                                  Eigen::Vector3d* gradient) {
    const contact::SurfaceQuery q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  const garment::TagconOptions tagcon;
  const garment::Construction construction = garment::construct(pattern, body, distance, tagcon);
  const auto mesh_start = Clock::now();
  const garment::GarmentMesh garment = garment::build_garment_mesh(construction, mesh_options);
  const double mesh_seconds = std::chrono::duration<double>(Clock::now() - mesh_start).count();

  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "%s: %zu panels in %zu packs; %zu seams, %zu lines unseamed; "
                              "construction %.4f s (placement %.4f s, seams %.4f s)\n",
                              path.c_str(), pattern.panels.size(), pattern.packs.size(),
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

  nlohmann::json summary = run_metadata(invocation, "construct");
  summary["pattern"] = path;
  summary["body"] = "default";
  summary["units"] = "m";
  summary["tagcon_options"] = {{"clearance_m", tagcon.clearance},
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
  summary["cylinders"] = cylinders;
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
  summary["packs"] = packs;
  nlohmann::json panels = nlohmann::json::array();
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    panels.push_back({{"id", pattern.panels[p].id},
                      {"tag", tag_json(pattern.panels[p].tag)},
                      {"fabric", pattern.panels[p].fabric},
                      {"material_id", p},
                      {"first_vertex", garment.first_vertex[p]},
                      {"triangles", garment.triangle_count[p]}});
  }
  summary["panels"] = panels;
  nlohmann::json seams = nlohmann::json::array();
  const auto seam_json = [&](const garment::FoundSeam& seam) {
    return nlohmann::json{{"kind", garment::name_of(seam.kind)},
                          {"line_a", construction.lines[std::size_t(seam.line_a)].id},
                          {"line_b", construction.lines[std::size_t(seam.line_b)].id},
                          {"reverse", seam.reverse},
                          {"certainty", seam.certainty},
                          {"M",
                           {{"distance", seam.score.distance},
                            {"orientation", seam.score.orientation},
                            {"length", seam.score.length},
                            {"curvature", seam.score.curvature},
                            {"seamable", seam.score.seamable}}}};
  };
  for (std::size_t k = 0; k < construction.seams.size(); ++k) {
    nlohmann::json entry = seam_json(construction.seams[k]);
    entry["in_seam_file"] =
        !construction.lines[std::size_t(construction.seams[k].line_a)].interior &&
        !construction.lines[std::size_t(construction.seams[k].line_b)].interior;
    seams.push_back(entry);
  }
  summary["seams"] = seams;
  nlohmann::json deleted = nlohmann::json::array();
  for (const auto& seam : construction.deleted)
    deleted.push_back(seam_json(seam));
  summary["deleted_seams"] = deleted;
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
  summary["lines"] = lines;
  summary["t_seams"] = nlohmann::json::array();
  for (const auto& seam : garment.t_seams)
    summary["t_seams"].push_back({{"name", seam.name},
                                  {"a", seam.a},
                                  {"b", seam.b},
                                  {"reverse", seam.reverse},
                                  {"certainty", seam.certainty}});
  summary["mesh"] = {{"vertices", garment.mesh.vertex_count()},
                     {"triangles", garment.mesh.triangle_count()},
                     {"edge_length_m", mesh_options.edge_length},
                     {"min_angle_deg", mesh_options.min_angle_deg}};
  summary["timings"] = {
      {"construction_seconds", construction.placement_seconds + construction.seam_seconds},
      {"placement_seconds", construction.placement_seconds},
      {"seam_seconds", construction.seam_seconds},
      {"body_setup_seconds", body_seconds},
      {"meshing_seconds", mesh_seconds}};

  if (is_root()) {
    make_output_directory(directory);
    garment::write_garment_obj(directory + "/garment.obj", garment, pattern);
    write_seams(directory + "/seams.json", garment.seams);
    write_json(directory + "/construct.json", summary);
    garment::SvgOptions svg;
    for (const auto& seam : construction.seams)
      svg.seams.push_back({construction.lines[std::size_t(seam.line_a)].id,
                           construction.lines[std::size_t(seam.line_b)].id, seam.certainty});
    garment::write_pattern_svg(directory + "/pattern_seams.svg", pattern, svg);
    write_file_atomically(
        directory + "/placement.svg",
        garment::placement_svg(construction, body.mesh.vertices, body.mesh.faces));
  }
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "wrote %s\n", directory.c_str()));
  return 0;
}

} // namespace sartor
