#pragma once
// Cloth self-contact (docs/contact.md#cloth-self-contact): a penalty that
// keeps every vertex at least `offset` (the cloth's thickness) from every
// triangle of the cloth that is not near it in the cloth itself,
// E = sum over pairs k (offset - d)^2 / 2 (element/point_triangle.hpp).
//
// The pairs couple vertices anywhere in the mesh and change as the cloth
// moves, so the form works on global vectors like the seams: every rank
// holds all positions (one scatter), assembles the pairs of the vertices it
// owns, and adds forces and Hessian blocks by global index. The Jacobian's
// structure holds the candidate pairs (closer than offset + margin at the
// last refresh, ClothProblem::refresh_couplings); a pair in contact that is
// not a candidate marks the structure stale, and the minimiser refreshes it
// and rebuilds the Jacobian (solvers/minimiser.cpp). The distance has no
// sign: a step bound (step_bound) keeps any vertex from passing through a
// triangle within a step, so each keeps its side.

#include "contact/cloth_pairs.hpp"
#include "element/point_triangle.hpp"
#include "fem/form.hpp"

#include <petscvec.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor {
class ClothProblem;
}

namespace sartor::fem {

struct SelfContactSettings {
  bool enabled = false;
  double offset = 2e-3;   // m: the distance layers keep (twice the bodies' offset)
  double stiffness = 0.0; // N/m per pair; 0: the largest membrane modulus
  // Pairs closer in the cloth than this many edges, or than near_radius
  // offsets along its edges at rest (a corner's small triangles), or
  // across a seam, are left out: a crease, a dart's fold or a seam is the
  // cloth's own shape, not two layers meeting.
  int rings = 2;
  static constexpr double near_radius = 3.0;
  // The penalty sets in smoothly over this fraction of the offset
  // (element/penalty_law.hpp); 0: the plain quadratic penalty.
  double onset = 0.0;
};

// What self-contact does at a state (every rank).
struct SelfContactReport {
  long pairs = 0;                 // (vertex, triangle) pairs inside the offset
  double min_distance = INFINITY; // m, over those pairs
  double normal_force = 0.0;      // N: the sum of the pairs' penalty forces
  long candidates = 0;            // pairs in the Jacobian's structure
  long refreshes = 0;             // structure refreshes so far
};

class SelfContactForm final : public CouplingForm {
public:
  // Collective. `first_dof[v]`: v's first global dof, -1 when pinned (the
  // same on every rank); `pin_index[v]`: v's pin, -1 when free; `assigned`:
  // the vertices whose pairs this rank assembles; `nearby`: per vertex, the
  // vertices whose triangles it has no pairs with (contact::nearby_vertices).
  SelfContactForm(const ClothProblem& problem, Vec layout, const SelfContactSettings& settings,
                  double stiffness, std::vector<PetscInt> first_dof, std::vector<int> pin_index,
                  std::vector<bool> assigned, std::vector<std::vector<int>> nearby);
  ~SelfContactForm() override;
  SelfContactForm(const SelfContactForm&) = delete;
  SelfContactForm& operator=(const SelfContactForm&) = delete;

  const char* name() const override { return "self_contact"; }
  EnergyPart part() const override { return EnergyPart::contact; }
  PetscErrorCode energy(Vec x, double* energy) override;
  PetscErrorCode add_gradient(Vec x, Vec f) override;
  PetscErrorCode add_hessian(Vec x, bool exact, Mat J) override;
  PetscErrorCode record_couplings(Mat recording) override;

  // Collective: the candidate pairs at x; `changed`: whether they differ from
  // the last (the Jacobian must then be created anew).
  PetscErrorCode refresh(Vec x, bool* changed);
  // Collective: whether a Hessian since the last refresh left out a pair in
  // contact that is not a candidate.
  PetscErrorCode stale(bool* stale) const;
  // Collective: the largest t in (0, 1] such that no pair comes closer along
  // x + t d than the smaller of half its distance at x and a tenth of the
  // offset, by additive continuous collision detection (conservative
  // advancement on the distance and the pair's largest motion).
  PetscErrorCode step_bound(Vec x, Vec direction, double* bound);
  // Collective.
  PetscErrorCode report(Vec x, SelfContactReport* report);

  double stiffness() const { return stiffness_; }
  double offset() const { return settings_.offset; }
  const SelfContactSettings& settings() const { return settings_; }
  long refreshes() const { return refreshes_; }

private:
  // All vertex positions at x (pinned vertices at their places), every rank.
  PetscErrorCode positions(Vec x, std::vector<Eigen::Vector3d>* all);
  // The pairs this rank assembles closer than `radius`.
  std::vector<contact::VertexTrianglePair> pairs(const std::vector<Eigen::Vector3d>& all,
                                                 double radius) const;
  element::Vector12 stacked(const std::vector<Eigen::Vector3d>& all, int vertex,
                            int triangle) const;
  std::array<PetscInt, 12> rows(int vertex, int triangle) const;
  bool is_candidate(int vertex, int triangle) const;
  // The penalty's onset band, m.
  double band() const { return settings_.onset * settings_.offset; }

  const ClothProblem& problem_;
  SelfContactSettings settings_;
  double stiffness_;
  std::vector<PetscInt> first_dof_;
  std::vector<int> pin_index_;
  std::vector<bool> assigned_;
  std::vector<std::vector<int>> nearby_;
  double margin_ = 0.0; // m: candidates reach this far beyond the offset
  double reach_ = 0.0;  // m: the step bound's search for pairs reaches no farther
  std::vector<contact::VertexTrianglePair> candidates_;
  long refreshes_ = 0;
  bool stale_ = false;
  VecScatter to_all_ = nullptr;
  Vec all_ = nullptr;
};

} // namespace sartor::fem
