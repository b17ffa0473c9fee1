#include "app/contact_case.hpp"

#include "app/commands.hpp"

#include "common/error.hpp"
#include "contact/body_spec.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace sartor {

const std::vector<OptionSpec>& contact_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"body", "SPEC", "",
           "a rigid body, e.g. \"sphere center=0,0,0 radius=0.3 mu=0.3\" (docs/contact.md)", true},
          {"contact-offset", "M", "0.001", "distance kept between cloth vertices and bodies, m"},
          {"contact-stiffness", "N/M", "",
           "penalty stiffness per vertex, N/m [factor * E_max * vertex area / h^2]"},
          {"contact-stiffness-factor", "C", "1", "the factor of the automatic penalty stiffness"},
          {"contact-penalty-onset", "F", "0",
           "the penalty's force sets in smoothly over this fraction of the offset, 0 to 1 "
           "(0: the plain quadratic penalty; docs/contact.md#normal-contact-penalty)"},
          {"contact-edge-spacing", "M", "0",
           "penalty samples along cloth edges at most this far apart, m (0: vertices only; "
           "static drapes: 0.015)"},
          {"drape-support-radius", "M", "",
           "report the Cusick drape coefficient for a support disk of this radius, m"},
          {"self-contact", "", "",
           "cloth self-contact: no vertex comes closer than --contact-self-offset to a triangle "
           "of the cloth (docs/contact.md#cloth-self-contact)"},
          {"self-contact-offset", "M", "0.002", "the distance layers of cloth keep, m"},
          {"self-contact-stiffness", "N/M", "",
           "self-contact penalty stiffness per pair, N/m [the largest membrane modulus]"},
          {"self-contact-onset", "F", "0",
           "the self-contact penalty's force sets in smoothly over F times "
           "--self-contact-offset (a C^2 energy, as --contact-penalty-onset for the bodies); 0: "
           "the plain quadratic"},
          {"self-contact-rings", "N", "2",
           "pairs fewer edges apart in the cloth (or across a seam) have no self-contact"},
      },
      {"contact"},
      {{"drape-support-radius", "contact-support-radius"},
       {"self-contact", "contact-self"},
       {"self-contact-offset", "contact-self-offset"},
       {"self-contact-stiffness", "contact-self-stiffness"},
       {"self-contact-onset", "contact-self-onset"},
       {"self-contact-rings", "contact-self-rings"}});
  return specs;
}

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v[0], v[1], v[2]};
}

} // namespace

ContactCase read_contact_case(const Options& options) {
  ContactCase contact;
  std::set<std::string> names;
  for (const auto& [option, spec] : options.indexed("body")) {
    contact::Body body = contact::parse_body(spec, "option --" + option, option);
    if (!names.insert(body.name()).second) {
      throw InputError("option --" + option + ": a body is already named '" + body.name() + "'");
    }
    contact.bodies.push_back(std::move(body));
  }
  contact.settings.offset = options.positive_real("contact-offset");
  if (options.is_set("contact-stiffness")) {
    contact.settings.stiffness = options.positive_real("contact-stiffness");
  }
  contact.settings.stiffness_factor = options.positive_real("contact-stiffness-factor");
  contact.settings.edge_sample_spacing = options.nonnegative_real("contact-edge-spacing");
  contact.settings.penalty_onset = options.nonnegative_real("contact-penalty-onset");
  if (contact.settings.penalty_onset > 1.0)
    throw InputError("option --contact-penalty-onset: " + options.text("contact-penalty-onset") +
                     " is more than 1 (the band would reach past the offset)");
  if (options.is_set("drape-support-radius"))
    contact.support_radius = options.positive_real("drape-support-radius");
  contact.self_contact.enabled = options.flag("self-contact");
  contact.self_contact.offset = options.positive_real("self-contact-offset");
  if (options.is_set("self-contact-stiffness"))
    contact.self_contact.stiffness = options.positive_real("self-contact-stiffness");
  contact.self_contact.onset = options.nonnegative_real("self-contact-onset");
  if (contact.self_contact.onset > 1.0)
    throw InputError("option --self-contact-onset: " + options.text("self-contact-onset") +
                     " is more than 1 (the band would reach past the offset)");
  const long rings = options.integer("self-contact-rings");
  if (rings < 1 || rings > 10)
    throw InputError("option --self-contact-rings: " + std::to_string(rings) +
                     " is not between 1 and 10");
  contact.self_contact.rings = int(rings);
  return contact;
}

nlohmann::json attach_bone_intervals(const Options& options, double interval,
                                     ClothProblem& problem) {
  nlohmann::json report = nlohmann::json::array();
  const auto specs = options.indexed("body");
  if (problem.bodies.size() < specs.size())
    throw std::logic_error("attach_bone_intervals: the problem lacks the options' bodies");
  // set_up_contact put the options' bodies last, in this order.
  std::size_t b = problem.bodies.size() - specs.size();
  for (const auto& [option, spec] : specs) {
    contact::Body& body = problem.bodies[b++];
    const double started = process_cpu_seconds();
    body.bone_intervals = contact::body_bone_intervals(spec, "option --" + option, interval);
    if (!body.bone_intervals) continue;
    const contact::BoneIntervals& index = *body.bone_intervals;
    report.push_back({{"body", body.name()},
                      {"bones", index.bones()},
                      {"interval_m", interval},
                      {"intervals", index.intervals()},
                      {"triangles", index.triangles()},
                      {"largest_interval", index.largest_interval()},
                      {"intervals_outside", index.intervals_outside()},
                      {"build_cpu_s", process_cpu_seconds() - started}});
  }
  return report;
}

void set_up_self_contact(const ContactCase& contact, ClothProblem& problem) {
  if (contact.self_contact.enabled) problem.set_self_contact(contact.self_contact);
}

void set_up_contact(const ContactCase& contact, ClothProblem& problem) {
  problem.bodies.insert(problem.bodies.end(), contact.bodies.begin(), contact.bodies.end());
  problem.contact.offset = contact.settings.offset;
  problem.contact.stiffness = contact.settings.stiffness;
  problem.contact.stiffness_factor = contact.settings.stiffness_factor;
  problem.contact.edge_sample_spacing = contact.settings.edge_sample_spacing;
  problem.contact.penalty_onset = contact.settings.penalty_onset;
}

double projected_area(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& positions,
                      int resolution) {
  Eigen::Vector2d lower = positions.front().head<2>(), upper = lower;
  for (const auto& p : positions) {
    lower = lower.cwiseMin(p.head<2>());
    upper = upper.cwiseMax(p.head<2>());
  }
  const Eigen::Vector2d cell = (upper - lower) / double(resolution);
  if (!(cell.minCoeff() > 0.0)) return 0.0;
  std::vector<bool> covered(std::size_t(resolution) * std::size_t(resolution), false);
  const auto index = [&](double value, int axis) {
    return std::clamp(int(std::floor((value - lower[axis]) / cell[axis] - 0.5)), 0, resolution - 1);
  };
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector2d a = positions[std::size_t(t[0])].head<2>();
    const Eigen::Vector2d b = positions[std::size_t(t[1])].head<2>();
    const Eigen::Vector2d c = positions[std::size_t(t[2])].head<2>();
    const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
      return u.x() * v.y() - u.y() * v.x();
    };
    const double twice_area = cross(b - a, c - a);
    if (twice_area == 0.0) continue;
    const Eigen::Vector2d low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
    // Cells whose centre lies in the triangle (barycentric signs).
    for (int i = index(low.x(), 0); i <= std::min(index(high.x(), 0) + 1, resolution - 1); ++i) {
      for (int j = index(low.y(), 1); j <= std::min(index(high.y(), 1) + 1, resolution - 1); ++j) {
        const Eigen::Vector2d p =
            lower + Eigen::Vector2d((i + 0.5) * cell.x(), (j + 0.5) * cell.y());
        const double u = cross(b - p, c - p) / twice_area;
        const double v = cross(c - p, a - p) / twice_area;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) {
          covered[std::size_t(i) * std::size_t(resolution) + std::size_t(j)] = true;
        }
      }
    }
  }
  const auto cells = std::count(covered.begin(), covered.end(), true);
  return double(cells) * cell.x() * cell.y();
}

int drape_nodes(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& positions,
                double prominence) {
  const auto flat_radius = [&](int v) { return mesh.positions[std::size_t(v)].head<2>().norm(); };
  const std::vector<int> boundary = boundary_vertices(mesh);
  double largest = 0.0;
  for (int v : boundary)
    largest = std::max(largest, flat_radius(v));
  std::vector<std::pair<double, double>> rim; // polar angle flat, radius draped
  for (int v : boundary) {
    if (flat_radius(v) < 0.99 * largest) continue;
    const Eigen::Vector3d& flat = mesh.positions[std::size_t(v)];
    rim.emplace_back(std::atan2(flat.y(), flat.x()), positions[std::size_t(v)].head<2>().norm());
  }
  if (rim.size() < 3) return 0;
  std::sort(rim.begin(), rim.end());
  // From the lowest radius once round and back to it: rising until the
  // radius falls `prominence` below the top (a node), then falling until it
  // rises `prominence` above the bottom.
  const auto lowest = std::min_element(
      rim.begin(), rim.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  const std::size_t start = std::size_t(lowest - rim.begin());
  bool rising = true;
  double top = lowest->second, bottom = lowest->second;
  int nodes = 0;
  for (std::size_t k = 1; k <= rim.size(); ++k) {
    const double r = rim[(start + k) % rim.size()].second;
    if (rising) {
      top = std::max(top, r);
      if (top - r >= prominence) {
        ++nodes;
        rising = false;
        bottom = r;
      }
    } else {
      bottom = std::min(bottom, r);
      if (r - bottom >= prominence) {
        rising = true;
        top = r;
      }
    }
  }
  return nodes;
}

CaseContact measure_contact(const ContactCase& contact, ClothProblem& problem, Vec x,
                            const std::vector<Eigen::Vector3d>& positions) {
  CaseContact result;
  result.settings = problem.contact;
  for (const contact::Body& body : problem.bodies)
    result.bodies.push_back(body.describe());
  SartorPetscCall(problem.contact_report(x, &result.reports));
  if (problem.has_self_contact()) {
    fem::SelfContactReport self;
    SartorPetscCall(problem.self_contact_report(x, &self));
    result.self_contact = self;
  }
  if (contact.support_radius) {
    const double radius = *contact.support_radius;
    DrapeMeasure drape;
    drape.support_area = M_PI * radius * radius;
    drape.specimen_area = material_area(problem.mesh());
    double area = positions.empty() ? 0.0 : projected_area(problem.mesh(), positions);
    MPI_Bcast(&area, 1, MPI_DOUBLE, 0, problem.comm());
    drape.projected_area = area;
    if (!(drape.specimen_area > drape.support_area)) {
      throw InputError("option --drape-support-radius: the support disk (" +
                       std::to_string(drape.support_area) +
                       " m^2) is not smaller than the specimen (" +
                       std::to_string(drape.specimen_area) + " m^2)");
    }
    drape.coefficient =
        (drape.projected_area - drape.support_area) / (drape.specimen_area - drape.support_area);
    // Folds rise and fall by centimetres; a hundredth of the specimen's
    // radius leaves out the ripples between mesh vertices.
    drape.node_prominence = 0.01 * std::sqrt(drape.specimen_area / M_PI);
    int nodes =
        positions.empty() ? 0 : drape_nodes(problem.mesh(), positions, drape.node_prominence);
    MPI_Bcast(&nodes, 1, MPI_INT, 0, problem.comm());
    drape.nodes = nodes;
    result.drape = drape;
  }
  return result;
}

nlohmann::json contact_summary(const CaseContact& contact) {
  nlohmann::json bodies = nlohmann::json::array();
  double penetration = 0.0;
  long contacting = 0;
  for (std::size_t b = 0; b < contact.reports.size(); ++b) {
    const BodyContact& r = contact.reports[b];
    penetration = std::max(penetration, r.max_penetration);
    contacting += r.contacting_vertices;
    bodies.push_back({{"body", contact.bodies[b]},
                      {"reaction_N", vector_json(r.normal_force + r.friction_force)},
                      {"normal_force_N", vector_json(r.normal_force)},
                      {"friction_force_N", vector_json(r.friction_force)},
                      {"contacting_vertices", r.contacting_vertices},
                      {"anchored_vertices", r.anchored_vertices},
                      {"sliding_vertices", r.sliding_vertices},
                      {"max_penetration_m", r.max_penetration},
                      {"min_distance_m", r.min_distance},
                      {"contacting_edge_samples", r.contacting_edge_samples},
                      {"edge_max_penetration_m", r.edge_max_penetration}});
  }
  nlohmann::json summary = {{"offset_m", contact.settings.offset},
                            {"stiffness_N_per_m", contact.settings.stiffness > 0.0
                                                      ? nlohmann::json(contact.settings.stiffness)
                                                      : nlohmann::json("automatic")},
                            {"stiffness_factor", contact.settings.stiffness_factor},
                            {"edge_sample_spacing_m", contact.settings.edge_sample_spacing},
                            {"penalty_onset", contact.settings.penalty_onset},
                            {"max_penetration_m", penetration},
                            {"contacting_vertices", contacting},
                            {"bodies", bodies}};
  if (contact.self_contact) {
    const fem::SelfContactReport& s = *contact.self_contact;
    summary["self_contact"] = {{"pairs", s.pairs},
                               {"min_distance_m", std::isfinite(s.min_distance)
                                                      ? nlohmann::json(s.min_distance)
                                                      : nlohmann::json(nullptr)},
                               {"normal_force_N", s.normal_force},
                               {"candidate_pairs", s.candidates},
                               {"structure_refreshes", s.refreshes}};
  }
  if (contact.drape) {
    summary["drape"] = {{"coefficient", contact.drape->coefficient},
                        {"nodes", contact.drape->nodes},
                        {"node_prominence_m", contact.drape->node_prominence},
                        {"projected_area_m2", contact.drape->projected_area},
                        {"support_area_m2", contact.drape->support_area},
                        {"specimen_area_m2", contact.drape->specimen_area}};
  }
  return summary;
}

} // namespace sartor
