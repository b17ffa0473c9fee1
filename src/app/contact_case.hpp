#pragma once
// Bodies and contact in a cloth case (docs/contact.md): the options that
// describe them, their set-up on a ClothProblem, and what summary.json
// reports: per-body reactions, penetration, contacting and sliding vertices,
// and the Cusick drape coefficient.

#include "app/cli.hpp"
#include "fem/cloth_problem.hpp"
#include "mesh/triangle_mesh.hpp"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The contact options (and --drape-support-radius), declared by this module.
const std::vector<OptionSpec>& contact_option_specs();

// The contact part of a case: the bodies, an indexed list (--body,
// --body2, ... --body99, in that order), and the penalty settings
// (--contact-offset, --contact-stiffness, --contact-stiffness-factor,
// --contact-edge-spacing), and the support disk of a Cusick drape
// (--drape-support-radius; none: not a drape test).
struct ContactCase {
  std::vector<contact::Body> bodies;
  ContactSettings settings;
  std::optional<double> support_radius; // m
  fem::SelfContactSettings self_contact;
};

// Throws InputError naming the option for a bad specification or two bodies
// of one name.
ContactCase read_contact_case(const Options& options);

void set_up_contact(const ContactCase& contact, ClothProblem& problem);
// The bone intervals (contact::body_bone_intervals, `interval` m) of each
// body of the options that has them, set on the problem's body made from
// that option (set_up_contact put them last, in the options' order) for
// push_out_of_bodies. Returns, per indexed body, its name, bones,
// intervals, triangles, the most triangles in one interval, the intervals
// not inside the mesh and the index's build time (CPU s).
nlohmann::json attach_bone_intervals(const Options& options, double interval,
                                     ClothProblem& problem);
// After the seams: cloth self-contact where the case asks for it.
void set_up_self_contact(const ContactCase& contact, ClothProblem& problem);

// The Cusick drape coefficient: the cloth's shadow on the horizontal plane
// (the area covered by its triangles projected along z) against the flat
// specimen's and the support disk's areas:
//     DC = (A_projected - A_support) / (A_specimen - A_support).
struct DrapeMeasure {
  double coefficient = 0.0;
  int nodes = 0;                // folds of the overhang (drape_nodes)
  double node_prominence = 0.0; // m, the radial rise and fall a node needs
  double projected_area = 0.0;  // m^2
  double support_area = 0.0;    // m^2
  double specimen_area = 0.0;   // m^2, the material area of the mesh
};

// Area covered by the triangles projected onto the xy plane, m^2 (overlaps
// counted once), by sampling a grid of `resolution` x `resolution` cells
// over their bounding box.
double projected_area(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& positions,
                      int resolution = 2000);

// The nodes (folds) of a draped circular specimen: the maxima of the rim's
// projected radius |(x, y)| at `positions`, going round the rim in the order
// of its vertices' polar angles in `mesh` (the flat specimen), counted with
// hysteresis: a node rises at least `prominence` above the lowest radius
// since the last node and falls at least `prominence` below its top before
// the next (ripples smaller than that are not folds). The rim is the
// boundary vertices within 1 % of the largest distance from the z axis.
int drape_nodes(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& positions,
                double prominence);

struct CaseContact {
  std::vector<std::string> bodies; // descriptions, in option order
  std::vector<BodyContact> reports;
  ContactSettings settings;
  std::optional<DrapeMeasure> drape;
  std::optional<fem::SelfContactReport> self_contact;
};

// Collective: the contact state at x; `positions` (rank 0) give the drape
// coefficient where `contact` has a support disk.
CaseContact measure_contact(const ContactCase& contact, ClothProblem& problem, Vec x,
                            const std::vector<Eigen::Vector3d>& positions);

// The "contact" object of summary.json.
nlohmann::json contact_summary(const CaseContact& contact);

} // namespace sartor
