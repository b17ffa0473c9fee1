#include "fem/cloth_problem.hpp"

#include "common/error.hpp"
#include "element/pressure.hpp"
#include "fem/block_assembly.hpp"
#include "fem/forms/contact_form.hpp"
#include "fem/forms/creep_coupling_form.hpp"
#include "fem/forms/load_forms.hpp"
#include "fem/forms/local_arrays.hpp"
#include "fem/forms/membrane_form.hpp"
#include "fem/forms/seam_form.hpp"
#include "fem/mesh_partition.hpp"
#include "fem/petsc_call.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sartor {

namespace {

constexpr PetscInt dofs_per_vertex = 3;
// The name under which a Jacobian carries its fem::ElementScatter.
constexpr const char* element_scatter_name = "sartor_element_scatter";

// Mesh index of every local point: cells as c >= 0, vertices as -(v + 1).
// `migration` maps the serial mesh's points (on rank 0) to the distributed
// ones; without it (one rank) the numbering is the serial one.
PetscErrorCode original_points(DM serial, PetscSF migration, DM distributed,
                               std::vector<PetscInt>* original) {
  PetscInt serial_start = 0, serial_end = 0, cell_end = 0, vertex_start = 0, vertex_end = 0;
  PetscInt chart_start = 0, chart_end = 0;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(serial, &serial_start, &serial_end));
  PetscCall(DMPlexGetHeightStratum(serial, 0, nullptr, &cell_end));
  PetscCall(DMPlexGetDepthStratum(serial, 0, &vertex_start, &vertex_end));
  // Edges keep a value no cell or vertex has; only cells and vertices are asked for.
  std::vector<PetscInt> serial_ids(std::size_t(serial_end - serial_start), PETSC_MAX_INT);
  for (PetscInt c = 0; c < cell_end; ++c)
    serial_ids[std::size_t(c)] = c;
  for (PetscInt p = vertex_start; p < vertex_end; ++p) {
    serial_ids[std::size_t(p)] = -(p - vertex_start + 1);
  }
  PetscCall(DMPlexGetChart(distributed, &chart_start, &chart_end));
  original->assign(std::size_t(chart_end - chart_start), 0);
  if (!migration) {
    *original = serial_ids;
    PetscFunctionReturn(0);
  }
  PetscCall(
      PetscSFBcastBegin(migration, MPIU_INT, serial_ids.data(), original->data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(migration, MPIU_INT, serial_ids.data(), original->data(), MPI_REPLACE));
  PetscFunctionReturn(0);
}

// Points this rank does not own are the leaves of the point SF.
PetscErrorCode foreign_points(DM dm, std::vector<bool>* foreign) {
  PetscSF sf = nullptr;
  PetscInt roots = 0, leaves = 0, start = 0, end = 0;
  const PetscInt* local = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &start, &end));
  foreign->assign(std::size_t(end - start), false);
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, &roots, &leaves, &local, nullptr));
  if (roots < 0) PetscFunctionReturn(0); // graph not set: one rank
  for (PetscInt i = 0; i < leaves; ++i)
    (*foreign)[std::size_t(local ? local[i] : i)] = true;
  PetscFunctionReturn(0);
}

using fem::gather;
using fem::scatter_add;

// The PETSc log event of a form ("form membrane", ...; "form triangles" for
// the pass over the triangles, which evaluates the triangle forms), so that
// -log_view shows where an evaluation's time goes. Registered on first use,
// in the same order on every rank (every rank has the same forms).
PetscLogEvent form_event(const std::string& form) {
  static PetscClassId forms_class = 0;
  static std::map<std::string, PetscLogEvent> events;
  if (!forms_class) SartorPetscCall(PetscClassIdRegister("Sartor forms", &forms_class));
  const auto [found, added] = events.try_emplace(form, 0);
  if (added)
    SartorPetscCall(PetscLogEventRegister(("form " + form).c_str(), forms_class, &found->second));
  return found->second;
}

// Runs `evaluate` (void, or returning a PetscErrorCode) under the form's
// log event.
template <class Evaluate>
PetscErrorCode logged(const std::string& form, Evaluate&& evaluate) {
  const PetscLogEvent event = form_event(form);
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(event, 0, 0, 0, 0));
  if constexpr (std::is_void_v<std::invoke_result_t<Evaluate>>) {
    evaluate();
  } else {
    PetscCall(evaluate());
  }
  PetscCall(PetscLogEventEnd(event, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// Every material uses the same bending model, and every triangle's
// material id names one.
void check_materials(const TriangleMesh& mesh, const std::vector<ClothMaterial>& materials) {
  if (materials.empty()) throw InputError("cloth: no material given");
  for (const ClothMaterial& material : materials) {
    if (material.bending_model != materials.front().bending_model) {
      throw InputError("cloth: all materials must use the same bending model");
    }
  }
  for (std::size_t t = 0; t < mesh.material_ids.size(); ++t) {
    const int id = mesh.material_ids[t];
    if (id < 0 || std::size_t(id) >= materials.size()) {
      throw InputError("cloth mesh: triangle " + std::to_string(t) + " has material id " +
                       std::to_string(id) + ", but there are " + std::to_string(materials.size()) +
                       " material(s)");
    }
  }
}

// The serial mesh lives on rank 0; DMPlexDistribute partitions it and adds
// one layer of overlap so that every owned hinge sees both its triangles.
// The distributed DM, and in `original` the mesh index of its every point
// (original_points' numbering).
DM distribute_mesh(MPI_Comm comm, PetscMPIInt rank, const TriangleMesh& mesh,
                   std::vector<PetscInt>* original) {
  std::vector<PetscInt> cells;
  std::vector<PetscReal> coordinates;
  if (rank == 0) {
    for (const auto& t : mesh.triangles)
      cells.insert(cells.end(), {t[0], t[1], t[2]});
    for (const auto& p : mesh.positions)
      coordinates.insert(coordinates.end(), {p[0], p[1], p[2]});
  }
  DM serial = nullptr;
  SartorPetscCall(
      DMPlexCreateFromCellListPetsc(comm, 2, rank == 0 ? PetscInt(mesh.triangle_count()) : 0,
                                    rank == 0 ? PetscInt(mesh.vertex_count()) : 0, 3, PETSC_TRUE,
                                    cells.data(), 3, coordinates.data(), &serial));
  SartorPetscCall(PetscObjectSetName(reinterpret_cast<PetscObject>(serial), "cloth"));
  // Only the partitioner is configurable here (-petscpartitioner_type):
  // DMSetFromOptions would already distribute the mesh, losing its numbering.
  PetscPartitioner partitioner = nullptr;
  SartorPetscCall(DMPlexGetPartitioner(serial, &partitioner));
  SartorPetscCall(PetscPartitionerSetFromOptions(partitioner));
  SartorPetscCall(set_default_partition(partitioner, comm, mesh));
  // Partition first, then add the overlap, carrying the mesh numbering of
  // every point through both migrations.
  DM distributed = nullptr, overlapping = nullptr;
  PetscSF migration = nullptr, overlap = nullptr;
  SartorPetscCall(DMPlexDistribute(serial, 0, &migration, &distributed));
  SartorPetscCall(original_points(serial, migration, distributed ? distributed : serial, original));
  DM dm = serial;
  if (distributed) {
    SartorPetscCall(DMDestroy(&serial));
    SartorPetscCall(DMPlexDistributeOverlap(distributed, 1, &overlap, &overlapping));
    std::vector<PetscInt> partitioned = std::move(*original);
    PetscInt start = 0, end = 0;
    SartorPetscCall(DMPlexGetChart(overlapping, &start, &end));
    original->assign(std::size_t(end - start), PETSC_MAX_INT);
    SartorPetscCall(
        PetscSFBcastBegin(overlap, MPIU_INT, partitioned.data(), original->data(), MPI_REPLACE));
    SartorPetscCall(
        PetscSFBcastEnd(overlap, MPIU_INT, partitioned.data(), original->data(), MPI_REPLACE));
    SartorPetscCall(DMDestroy(&distributed));
    dm = overlapping;
  }
  SartorPetscCall(PetscSFDestroy(&migration));
  SartorPetscCall(PetscSFDestroy(&overlap));
  return dm;
}

} // namespace

ClothProblem::ClothProblem(MPI_Comm comm, const TriangleMesh& mesh, const ClothMaterial& material,
                           const std::vector<int>& pinned)
    : ClothProblem(comm, mesh, std::vector<ClothMaterial>{material}, pinned) {}

ClothProblem::ClothProblem(MPI_Comm comm, const TriangleMesh& mesh,
                           std::vector<ClothMaterial> materials, const std::vector<int>& pinned,
                           const std::vector<double>& release_times)
    : comm_(comm), mesh_(mesh), materials_(std::move(materials)), pinned_(pinned),
      release_times_(release_times) {
  if (release_times_.empty()) release_times_.assign(pinned_.size(), INFINITY);
  if (release_times_.size() != pinned_.size()) {
    throw InputError("cloth: " + std::to_string(release_times_.size()) + " release times for " +
                     std::to_string(pinned_.size()) + " pins");
  }
  validate(mesh, "cloth mesh");
  check_materials(mesh, materials_);
  PetscMPIInt rank = 0;
  MPI_Comm_rank(comm, &rank);
  nonelastic.assign(mesh.triangle_count(), {});
  for (int v : pinned) {
    if (v < 0 || std::size_t(v) >= mesh.vertex_count()) {
      throw InputError("pinned vertex " + std::to_string(v) + " is not in the mesh (0.." +
                       std::to_string(mesh.vertex_count() - 1) + ")");
    }
    pin_positions_.push_back(mesh.positions[std::size_t(v)]);
  }

  std::vector<PetscInt> original;
  dm_ = distribute_mesh(comm, rank, mesh, &original);
  std::vector<bool> foreign;
  SartorPetscCall(foreign_points(dm_, &foreign));
  // Three dofs per vertex; pinned vertices are constrained, so the global
  // system holds the free dofs only.
  std::vector<bool> is_pinned(mesh.vertex_count(), false);
  for (std::size_t i = 0; i < pinned.size(); ++i)
    is_pinned[std::size_t(pinned[i])] = !releasable(i);
  set_up_dofs(original, foreign, is_pinned);
  const std::vector<bool> triangle_owned = set_up_triangles(original, foreign);
  triangle_forms_.push_back(std::make_unique<fem::MembraneForm>(nonelastic, nonelastic_response));
  triangle_forms_.push_back(
      std::make_unique<fem::CreepCouplingForm>(nonelastic, nonelastic_response));
  const std::vector<int> boundary = boundary_vertices(mesh);
  const bool boundary_held = std::all_of(boundary.begin(), boundary.end(),
                                         [&](int v) { return is_pinned[std::size_t(v)]; });
  triangle_forms_.push_back(std::make_unique<fem::SurfaceLoadForm>(loads, mesh_, boundary_held));
  set_up_bending(triangle_owned, is_pinned);
  forms_.push_back(std::make_unique<fem::PointLoadForm>(loads, mesh_, vertex_dof_, vertex_owned_));
  std::vector<bool> moves(mesh.vertex_count(), true); // free, or a pin that is let go
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    moves[std::size_t(pinned_[i])] = releasable(i);
  auto contact_form = std::make_unique<fem::ContactForm>(*this, vertex_dof_, vertex_owned_, moves,
                                                         triangle_owned, largest_modulus());
  contact_form_ = contact_form.get();
  forms_.push_back(std::move(contact_form));
}

void ClothProblem::add_form(std::unique_ptr<fem::Form> form) {
  if (form->part() == fem::EnergyPart::inertia) {
    throw std::invalid_argument(std::string("the form '") + form->name() +
                                "' is a time step's inertia, not a term of the cloth");
  }
  forms_.push_back(std::move(form));
}

std::vector<std::string> ClothProblem::form_names() const {
  std::vector<std::string> names;
  for (const auto& form : triangle_forms_)
    names.emplace_back(form->name());
  for (const auto& form : forms_)
    names.emplace_back(form->name());
  for (const auto& form : coupling_forms_)
    names.emplace_back(form->name());
  return names;
}

void ClothProblem::enable_form(const std::string& name, bool enabled) {
  const std::vector<std::string> names = form_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InputError("cloth: no form named '" + name + "'");
  disabled_forms_.erase(std::remove(disabled_forms_.begin(), disabled_forms_.end(), name),
                        disabled_forms_.end());
  if (!enabled) disabled_forms_.push_back(name);
}

template <class F>
std::vector<F*> ClothProblem::enabled(const std::vector<std::unique_ptr<F>>& all) const {
  std::vector<F*> forms;
  for (const auto& form : all) {
    if (form->active() && !disabled(form->name())) forms.push_back(form.get());
  }
  return forms;
}

std::vector<double> ClothProblem::event_times() const {
  std::vector<double> times;
  for (const PinGroupMotion& group : pin_groups) {
    for (const PinKnot& knot : group.history.knots())
      times.push_back(knot.time);
  }
  for (double release : release_times_) {
    if (std::isfinite(release)) times.push_back(release);
  }
  for (const contact::Body& body : bodies) {
    for (const std::vector<double>& knots :
         {body.motion.translation.times(), body.motion.angle.times(), body.motion.scale.times()})
      times.insert(times.end(), knots.begin(), knots.end());
  }
  return times;
}

bool ClothProblem::has_potential() const {
  const auto potential = [](const auto& form) { return form->has_potential(); };
  return std::all_of(triangle_forms_.begin(), triangle_forms_.end(), potential) &&
         std::all_of(forms_.begin(), forms_.end(), potential);
}

bool ClothProblem::symmetric_jacobian() const {
  // From the pins' release times, the same on every rank (the rows are
  // each rank's own), so that every rank chooses the same factorisation.
  for (std::size_t pin = 0; pin < pinned_.size(); ++pin)
    if (releasable(pin)) return false;
  return has_potential();
}

bool ClothProblem::projects_hessians() const {
  for (const ClothMaterial& m : materials_) {
    if (m.project_bending) return true; // the bending forms' elements
    for (const auto& form : triangle_forms_) {
      if (form->projects(m)) return true;
    }
  }
  return std::any_of(forms_.begin(), forms_.end(),
                     [](const auto& form) { return form->projects(); });
}

// The local section (three dofs per vertex, pinned ones constrained), the
// local vectors, each mesh vertex's local offset and owner, and the rows of
// the releasable pins this rank owns.
void ClothProblem::set_up_dofs(const std::vector<PetscInt>& original,
                               const std::vector<bool>& foreign,
                               const std::vector<bool>& is_pinned) {
  PetscInt vertex_start = 0, vertex_end = 0;
  SartorPetscCall(DMPlexGetDepthStratum(dm_, 0, &vertex_start, &vertex_end));
  PetscSection section = nullptr;
  SartorPetscCall(PetscSectionCreate(comm_, &section));
  PetscInt chart_start = 0, chart_end = 0;
  SartorPetscCall(DMPlexGetChart(dm_, &chart_start, &chart_end));
  SartorPetscCall(PetscSectionSetChart(section, chart_start, chart_end));
  for (PetscInt p = vertex_start; p < vertex_end; ++p) {
    SartorPetscCall(PetscSectionSetDof(section, p, dofs_per_vertex));
    const PetscInt v = -original[std::size_t(p)] - 1;
    if (is_pinned[std::size_t(v)]) SartorPetscCall(PetscSectionSetConstraintDof(section, p, 3));
  }
  SartorPetscCall(PetscSectionSetUp(section));
  const PetscInt all[3] = {0, 1, 2};
  for (PetscInt p = vertex_start; p < vertex_end; ++p) {
    const PetscInt v = -original[std::size_t(p)] - 1;
    if (is_pinned[std::size_t(v)])
      SartorPetscCall(PetscSectionSetConstraintIndices(section, p, all));
  }
  SartorPetscCall(DMSetLocalSection(dm_, section));
  SartorPetscCall(PetscSectionDestroy(&section));
  SartorPetscCall(DMCreateLocalVector(dm_, &local_x_));
  SartorPetscCall(VecDuplicate(local_x_, &local_f_));
  Vec global = nullptr;
  SartorPetscCall(DMGetGlobalVector(dm_, &global));
  SartorPetscCall(VecGetSize(global, &global_dofs_));
  SartorPetscCall(DMRestoreGlobalVector(dm_, &global));

  PetscSection local_section = nullptr;
  SartorPetscCall(DMGetLocalSection(dm_, &local_section));
  vertex_dof_.assign(mesh_.vertex_count(), -1);
  vertex_owned_.assign(mesh_.vertex_count(), false);
  for (PetscInt p = vertex_start; p < vertex_end; ++p) {
    const auto v = std::size_t(-original[std::size_t(p)] - 1);
    SartorPetscCall(PetscSectionGetOffset(local_section, p, &vertex_dof_[v]));
    vertex_owned_[v] = !foreign[std::size_t(p)];
  }
  ISLocalToGlobalMapping local_to_global = nullptr;
  SartorPetscCall(DMGetLocalToGlobalMapping(dm_, &local_to_global));
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    const auto v = std::size_t(pinned_[i]);
    if (!releasable(i) || !vertex_owned_[v]) continue;
    PetscInt row = 0;
    SartorPetscCall(ISLocalToGlobalMappingApply(local_to_global, 1, &vertex_dof_[v], &row));
    releasable_rows_.push_back({i, row});
  }
}

// Owned triangles (their rest shapes and dofs); which mesh triangles this
// rank owns.
std::vector<bool> ClothProblem::set_up_triangles(const std::vector<PetscInt>& original,
                                                 const std::vector<bool>& foreign) {
  PetscInt cell_start = 0, cell_end = 0;
  SartorPetscCall(DMPlexGetHeightStratum(dm_, 0, &cell_start, &cell_end));
  std::vector<bool> triangle_owned(mesh_.triangle_count(), false);
  for (PetscInt c = cell_start; c < cell_end; ++c) {
    if (foreign[std::size_t(c)]) continue;
    const auto t = std::size_t(original[std::size_t(c)]);
    triangle_owned[t] = true;
    LocalTriangle local;
    local.index = int(t);
    local.material = &triangle_material(t);
    local.rest = element::triangle_rest(mesh_.material_uv[t]);
    for (std::size_t k = 0; k < 3; ++k) {
      const PetscInt offset = vertex_dof_[std::size_t(mesh_.triangles[t][k])];
      if (offset < 0) throw std::logic_error("a vertex of an owned triangle is not local");
      for (std::size_t d = 0; d < 3; ++d)
        local.dofs[3 * k + d] = offset + PetscInt(d);
    }
    triangles_.push_back(local);
  }
  return triangle_owned;
}

ClothProblem::~ClothProblem() {
  VecDestroy(&local_x_);
  VecDestroy(&local_f_);
  DMDestroy(&dm_);
}

PetscErrorCode ClothProblem::lumped_mass(Vec mass) {
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecSet(local_f_, 0.0));
  PetscCall(VecGetArray(local_f_, &values));
  for (const LocalTriangle& t : triangles_) {
    const double density = t.material->areal_density > 0.0 ? t.material->areal_density : 1.0;
    for (PetscInt dof : t.dofs)
      values[dof] += density * t.rest.area / 3.0;
  }
  PetscCall(VecRestoreArray(local_f_, &values));
  PetscCall(VecSet(mass, 0.0));
  PetscCall(DMLocalToGlobal(dm_, local_f_, ADD_VALUES, mass));
  PetscFunctionReturn(0);
}

double ClothProblem::force_scale() const {
  double area = 0.0;
  for (const auto& uv : mesh_.material_uv) {
    area += 0.5 * std::abs((uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() -
                           (uv[2] - uv[0]).x() * (uv[1] - uv[0]).y());
  }
  return largest_modulus() * std::sqrt(area);
}

const ClothMaterial& ClothProblem::triangle_material(std::size_t triangle) const {
  return mesh_.material_ids.empty() ? materials_.front()
                                    : materials_[std::size_t(mesh_.material_ids[triangle])];
}

double ClothProblem::largest_modulus() const {
  double modulus = 0.0;
  for (const ClothMaterial& material : materials_) {
    modulus = std::max({modulus, material.membrane.warp.initial_modulus(),
                        material.membrane.weft.initial_modulus()});
  }
  return modulus;
}

void ClothProblem::set_pin_position(std::size_t index, const Eigen::Vector3d& position) {
  pin_positions_.at(index) = position;
}

PetscErrorCode ClothProblem::create_solution(Vec* x) const {
  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(dm_, x));
  PetscCall(VecSetBlockSize(*x, dofs_per_vertex));
  PetscCall(set_solution(mesh_.positions, *x));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::set_solution(const std::vector<Eigen::Vector3d>& positions,
                                          Vec x) const {
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCheck(positions.size() == mesh_.vertex_count(), comm_, PETSC_ERR_ARG_SIZ,
             "%zu positions for a mesh of %zu vertices", positions.size(), mesh_.vertex_count());
  PetscCall(VecSet(local_x_, 0.0));
  PetscCall(VecGetArray(local_x_, &values));
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (vertex_dof_[v] < 0) continue;
    for (std::size_t d = 0; d < 3; ++d)
      values[vertex_dof_[v] + PetscInt(d)] = positions[v][long(d)];
  }
  PetscCall(VecRestoreArray(local_x_, &values));
  PetscCall(DMLocalToGlobal(dm_, local_x_, INSERT_VALUES, x));
  PetscFunctionReturn(0);
}

// Where every pin is now, in the order of pinned().
PetscErrorCode ClothProblem::pin_places(std::vector<Eigen::Vector3d>* places) const {
  PetscFunctionBeginUser;
  *places = pin_positions_;
  const double clock = pins_follow_time ? time : load_factor;
  for (const PinGroupMotion& group : pin_groups) {
    for (std::size_t i : group.pins) {
      PetscCheck(i < places->size(), comm_, PETSC_ERR_ARG_OUTOFRANGE,
                 "pin group names pin %zu of %zu", i, places->size());
      (*places)[i] = group.place(pin_positions_[i], clock);
    }
  }
  for (Eigen::Vector3d& place : *places)
    place += load_factor * pin_motion;
  PetscFunctionReturn(0);
}

// The local positions: free dofs from x, pinned ones from their prescribed place.
PetscErrorCode ClothProblem::to_local(Vec x) {
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(dm_, x, INSERT_VALUES, local_x_));
  std::vector<Eigen::Vector3d> places;
  PetscCall(pin_places(&places));
  PetscCall(VecGetArray(local_x_, &values));
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    const PetscInt offset = vertex_dof_[std::size_t(pinned_[i])];
    if (offset < 0 || releasable(i)) continue; // a releasable pin's place is its equation's
    const Eigen::Vector3d& place = places[i];
    for (std::size_t d = 0; d < 3; ++d)
      values[offset + PetscInt(d)] = place[long(d)];
  }
  PetscCall(VecRestoreArray(local_x_, &values));
  PetscFunctionReturn(0);
}

bool ClothProblem::holds(std::size_t pin) const {
  return !pins_follow_time || time < release_times_[pin] ||
         (hold_at_release && time == release_times_[pin]);
}

PetscErrorCode ClothProblem::holding_rows(std::vector<HeldRow>* rows) const {
  PetscFunctionBeginUser;
  rows->clear();
  if (releasable_rows_.empty()) PetscFunctionReturn(0);
  std::vector<Eigen::Vector3d> places;
  PetscCall(pin_places(&places));
  for (const ReleasableRow& r : releasable_rows_) {
    if (holds(r.pin)) rows->push_back({r.row, places[r.pin]});
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::hold(Vec x) {
  std::vector<HeldRow> rows;
  PetscInt start = 0;
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(holding_rows(&rows));
  PetscCall(VecGetOwnershipRange(x, &start, nullptr));
  PetscCall(VecGetArray(x, &values));
  for (const HeldRow& r : rows) {
    for (PetscInt d = 0; d < 3; ++d)
      values[r.first - start + d] = r.place[long(d)];
  }
  PetscCall(VecRestoreArray(x, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::replace_held_rows(Vec x, Vec f) {
  std::vector<HeldRow> rows;
  PetscInt start = 0;
  const PetscScalar* positions = nullptr;
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(holding_rows(&rows));
  PetscCall(VecGetOwnershipRange(x, &start, nullptr));
  PetscCall(VecGetArrayRead(x, &positions));
  PetscCall(VecGetArray(f, &values));
  const double scale = largest_modulus();
  for (const HeldRow& r : rows) {
    for (PetscInt d = 0; d < 3; ++d) {
      const PetscInt i = r.first - start + d;
      values[i] = scale * (positions[i] - r.place[long(d)]);
    }
  }
  PetscCall(VecRestoreArray(f, &values));
  PetscCall(VecRestoreArrayRead(x, &positions));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::replace_held_rows(Mat J) {
  std::vector<HeldRow> held;
  PetscFunctionBeginUser;
  PetscCall(holding_rows(&held));
  std::vector<PetscInt> rows;
  for (const HeldRow& r : held)
    rows.insert(rows.end(), {r.first, r.first + 1, r.first + 2});
  bool any = !rows.empty(), anywhere = false;
  PetscCallMPI(MPIU_Allreduce(&any, &anywhere, 1, MPI_C_BOOL, MPI_LOR, comm_));
  if (anywhere) {
    PetscCall(
        MatZeroRows(J, PetscInt(rows.size()), rows.data(), largest_modulus(), nullptr, nullptr));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::accept_step(Vec x) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  for (const auto& form : forms_) {
    const PetscErrorCode failed = form->accept_step(form_point(values));
    if (failed) PetscCall(VecRestoreArrayRead(local_x_, &values));
    PetscCall(failed);
  }
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::update_contact(Vec x) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  const PetscErrorCode failed = contact_form_->accept_step(form_point(values));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(failed);
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::level_friction_anchors(Vec x) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  contact_form_->level_anchors(values);
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::energy(Vec x, ClothEnergy* result) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  const fem::FormPoint at = form_point(values);
  double local[fem::energy_part_count] = {};
  const std::vector<fem::TriangleForm*> triangle_forms = enabled(triangle_forms_);
  PetscCall(logged("triangles", [&] {
    for (const LocalTriangle& t : triangles_) {
      const element::Vector9 xe = gather<9>(values, t.dofs);
      for (const auto* form : triangle_forms)
        form->add_energy(triangle_view(t, xe), at, &local[int(form->part())]);
    }
  }));
  for (auto* form : enabled(forms_))
    PetscCall(logged(form->name(), [&] { form->add_energy(at, &local[int(form->part())]); }));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  double total[fem::energy_part_count];
  PetscCallMPI(MPIU_Allreduce(local, total, fem::energy_part_count, MPI_DOUBLE, MPI_SUM, comm_));
  for (auto* form : enabled(coupling_forms_)) {
    double energy = 0.0;
    PetscCall(logged(form->name(), [&] { return form->energy(x, &energy); }));
    total[int(form->part())] += energy;
  }
  using fem::EnergyPart;
  *result = {total[int(EnergyPart::membrane)], total[int(EnergyPart::bending)],
             total[int(EnergyPart::external)], total[int(EnergyPart::contact)],
             total[int(EnergyPart::seam)]};
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::residual(Vec x, Vec f) {
  const PetscScalar* values = nullptr;
  PetscScalar* forces = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecSet(local_f_, 0.0));
  PetscCall(VecGetArrayRead(local_x_, &values));
  PetscCall(VecGetArray(local_f_, &forces));
  const fem::FormPoint at = form_point(values);
  const std::vector<fem::TriangleForm*> triangle_forms = enabled(triangle_forms_);
  PetscCall(logged("triangles", [&] {
    for (const LocalTriangle& t : triangles_) {
      const element::Vector9 xe = gather<9>(values, t.dofs);
      for (const auto* form : triangle_forms)
        scatter_add<9>(forces, t.dofs, form->gradient(triangle_view(t, xe), at));
    }
  }));
  for (auto* form : enabled(forms_))
    PetscCall(logged(form->name(), [&] { form->add_gradient(at, forces); }));
  PetscCall(VecRestoreArray(local_f_, &forces));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(VecSet(f, 0.0));
  PetscCall(DMLocalToGlobal(dm_, local_f_, ADD_VALUES, f));
  for (auto* form : enabled(coupling_forms_))
    PetscCall(logged(form->name(), [&] { return form->add_gradient(x, f); }));
  PetscCall(replace_held_rows(x, f));
  PetscFunctionReturn(0);
}

// The triangle forms' Hessians, summed per triangle into one block.
PetscErrorCode ClothProblem::triangle_hessians(const fem::FormPoint& at,
                                               fem::ElementHessians& out) const {
  PetscFunctionBeginUser;
  const std::vector<fem::TriangleForm*> triangle_forms = enabled(triangle_forms_);
  for (const LocalTriangle& t : triangles_) {
    const element::Vector9 xe = gather<9>(at.x, t.dofs);
    fem::Matrix9 block = fem::Matrix9::Zero();
    for (const auto* form : triangle_forms)
      form->add_hessian(triangle_view(t, xe), at, block);
    PetscCall(out.add<9>(t.dofs, block));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::jacobian(Vec x, Mat J) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(MatZeroEntries(J));
  PetscCall(VecGetArrayRead(local_x_, &values));
  const fem::FormPoint at = form_point(values);
  // Element matrices go straight into the value arrays when create_jacobian
  // left a scatter with J, through MatSetValuesLocal otherwise.
  PetscContainer container = nullptr;
  fem::ElementScatter* scatter = nullptr;
  PetscCall(PetscObjectQuery(reinterpret_cast<PetscObject>(J), element_scatter_name,
                             reinterpret_cast<PetscObject*>(&container)));
  if (container) PetscCall(PetscContainerGetPointer(container, reinterpret_cast<void**>(&scatter)));
  // The scatter walks every registered element in order: with a form left
  // out, the blocks go through MatSetValuesLocal.
  if (!disabled_forms_.empty()) scatter = nullptr;
  if (scatter) PetscCall(scatter->begin());
  fem::ElementHessians elements(J, scatter);
  PetscCall(logged("triangles", [&] { return triangle_hessians(at, elements); }));
  for (auto* form : enabled(forms_))
    PetscCall(logged(form->name(), [&] { return form->add_element_hessians(at, elements); }));
  if (scatter) PetscCall(scatter->end());
  for (auto* form : enabled(forms_))
    PetscCall(logged(form->name(), [&] { return form->add_hessian(at, J); }));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  for (auto* form : enabled(coupling_forms_)) // global indices, across partitions
    PetscCall(logged(form->name(), [&] { return form->add_hessian(x, exact_hessian, J); }));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscCall(replace_held_rows(J));
  PetscFunctionReturn(0);
}

bool ClothProblem::has_rest_derivative() const {
  const auto has = [](const auto* form) { return form->has_rest_derivative(); };
  const auto all = [&](const auto& forms) { return std::all_of(forms.begin(), forms.end(), has); };
  return all(enabled(triangle_forms_)) && all(enabled(forms_)) && all(enabled(coupling_forms_));
}

PetscErrorCode ClothProblem::rest_derivative(Vec x, const RestChange& change, Vec derivative) {
  const PetscScalar* values = nullptr;
  PetscScalar* changes = nullptr;
  PetscFunctionBeginUser;
  PetscCheck(change.size() == mesh_.triangle_count(), comm_, PETSC_ERR_ARG_SIZ,
             "rest change of %zu triangles for a mesh of %zu", change.size(),
             mesh_.triangle_count());
  const std::vector<fem::TriangleForm*> triangle_forms = enabled(triangle_forms_);
  const std::vector<fem::Form*> forms = enabled(forms_);
  for (const auto* form : triangle_forms)
    PetscCheck(form->has_rest_derivative(), comm_, PETSC_ERR_SUP,
               "the form '%s' has no rest derivative", form->name());
  for (const auto* form : forms)
    PetscCheck(form->has_rest_derivative(), comm_, PETSC_ERR_SUP,
               "the form '%s' has no rest derivative", form->name());
  const std::vector<fem::CouplingForm*> coupling_forms = enabled(coupling_forms_);
  for (const auto* form : coupling_forms)
    PetscCheck(form->has_rest_derivative(), comm_, PETSC_ERR_SUP,
               "the form '%s' has no rest derivative", form->name());
  PetscCall(to_local(x));
  PetscCall(VecSet(local_f_, 0.0));
  PetscCall(VecGetArrayRead(local_x_, &values));
  PetscCall(VecGetArray(local_f_, &changes));
  const fem::FormPoint at = form_point(values);
  for (const LocalTriangle& t : triangles_) {
    const element::Vector9 xe = gather<9>(values, t.dofs);
    for (const auto* form : triangle_forms) {
      scatter_add<9>(changes, t.dofs,
                     form->rest_derivative(triangle_view(t, xe), at, change[std::size_t(t.index)]));
    }
  }
  for (const auto* form : forms)
    form->add_rest_derivative(at, change, changes);
  PetscCall(VecRestoreArray(local_f_, &changes));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(VecSet(derivative, 0.0));
  PetscCall(DMLocalToGlobal(dm_, local_f_, ADD_VALUES, derivative));
  for (auto* form : coupling_forms)
    PetscCall(form->add_rest_derivative(x, change, derivative));
  // The rows of pins that hold are x = place, whatever the pattern.
  std::vector<HeldRow> held;
  PetscInt start = 0;
  PetscCall(holding_rows(&held));
  PetscCall(VecGetOwnershipRange(derivative, &start, nullptr));
  PetscCall(VecGetArray(derivative, &changes));
  for (const HeldRow& r : held) {
    for (PetscInt d = 0; d < 3; ++d)
      changes[r.first - start + d] = 0.0;
  }
  PetscCall(VecRestoreArray(derivative, &changes));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::create_jacobian(Mat* J) {
  ISLocalToGlobalMapping map = nullptr;
  PetscInt local_size = 0;
  Vec global = nullptr;
  fem::BlockLayout layout;
  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm_, &global));
  PetscCall(VecGetLocalSize(global, &local_size));
  PetscCall(DMRestoreGlobalVector(dm_, &global));
  PetscCall(DMGetLocalToGlobalMapping(dm_, &map));
  PetscCall(fem::block_layout(dm_, &layout));
  PetscCall(MatCreate(comm_, J));
  PetscCall(MatSetSizes(*J, local_size, local_size, global_dofs_, global_dofs_));
  PetscCall(MatSetBlockSize(*J, dofs_per_vertex));
  PetscCall(MatSetType(*J, MATAIJ));
  PetscCall(MatSetOptionsPrefix(*J, "jacobian_"));
  PetscCall(MatSetFromOptions(*J));
  PetscCall(MatSetLocalToGlobalMapping(*J, map, map));

  // The exact block structure: every vertex pair of an element, plus the
  // couplings that other terms insert into `recording` (global indices).
  fem::BlockPattern pattern(comm_, layout);
  fem::ElementRegistry registry(&pattern, nullptr);
  PetscCall(register_elements(registry));
  Mat recording = nullptr;
  PetscCall(pattern.recorder(&recording));
  for (const auto& form : coupling_forms_)
    PetscCall(form->record_couplings(recording)); // global indices
  PetscCall(pattern.preallocate(*J));
  PetscCall(MatSetOption(*J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  // Held rows are zeroed in place: the element scatter keeps its positions.
  PetscCall(MatSetOption(*J, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  PetscCall(attach_element_scatter(layout, *J));
  PetscFunctionReturn(0);
}

// Every element whose block jacobian() adds, in that order: the triangles,
// then each form's.
PetscErrorCode ClothProblem::register_elements(fem::ElementRegistry& registry) const {
  PetscFunctionBeginUser;
  for (const LocalTriangle& t : triangles_)
    PetscCall(registry.add(t.dofs));
  for (const auto& form : forms_)
    PetscCall(form->register_elements(registry));
  PetscFunctionReturn(0);
}

// For AIJ matrices, where each element block lands in the value arrays, so
// that jacobian() adds element matrices without searching (kept with J).
PetscErrorCode ClothProblem::attach_element_scatter(const fem::BlockLayout& layout, Mat J) const {
  PetscBool aij = PETSC_FALSE;
  PetscContainer container = nullptr;
  PetscFunctionBeginUser;
  PetscCall(
      PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(J), &aij, MATSEQAIJ, MATMPIAIJ, ""));
  if (!aij) PetscFunctionReturn(0);
  auto scatter = std::make_unique<fem::ElementScatter>(layout);
  PetscCall(scatter->attach(J));
  fem::ElementRegistry registry(nullptr, scatter.get());
  PetscCall(register_elements(registry));
  PetscCall(PetscContainerCreate(PETSC_COMM_SELF, &container));
  PetscCall(PetscContainerSetPointer(container, scatter.release()));
  PetscCall(PetscContainerSetUserDestroy(container, [](void* pointer) -> PetscErrorCode {
    delete static_cast<fem::ElementScatter*>(pointer);
    return 0;
  }));
  PetscCall(PetscObjectCompose(reinterpret_cast<PetscObject>(J), element_scatter_name,
                               reinterpret_cast<PetscObject>(container)));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::gather_positions(Vec x, std::vector<Eigen::Vector3d>* positions) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  PetscCall(gather_vertex_triples(values, positions));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::positions_everywhere(Vec x, std::vector<Eigen::Vector3d>* positions) {
  PetscFunctionBeginUser;
  PetscCall(gather_positions(x, positions));
  unsigned long count = positions->size();
  PetscCallMPI(MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, comm_));
  positions->resize(count);
  PetscCallMPI(MPI_Bcast(positions->data()->data(), int(3 * count), MPI_DOUBLE, 0, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::gather_vertex_triples(const PetscScalar* local,
                                                   std::vector<Eigen::Vector3d>* triples) {
  Vec natural = nullptr, root = nullptr;
  VecScatter to_root = nullptr;
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  const auto n = PetscInt(mesh_.vertex_count());
  PetscCall(VecCreateMPI(comm_, PETSC_DECIDE, 3 * n, &natural));
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (!vertex_owned_[v]) continue;
    const PetscInt rows[3] = {3 * PetscInt(v), 3 * PetscInt(v) + 1, 3 * PetscInt(v) + 2};
    PetscCall(VecSetValues(natural, 3, rows, local + vertex_dof_[v], INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(natural));
  PetscCall(VecAssemblyEnd(natural));
  PetscCall(VecScatterCreateToZero(natural, &to_root, &root));
  PetscCall(VecScatterBegin(to_root, natural, root, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_root, natural, root, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt size = 0;
  PetscCall(VecGetLocalSize(root, &size));
  triples->clear();
  PetscCall(VecGetArrayRead(root, &values));
  for (PetscInt v = 0; v < size / 3; ++v) {
    triples->emplace_back(values[3 * v], values[3 * v + 1], values[3 * v + 2]);
  }
  PetscCall(VecRestoreArrayRead(root, &values));
  PetscCall(VecScatterDestroy(&to_root));
  PetscCall(VecDestroy(&root));
  PetscCall(VecDestroy(&natural));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::gather_strains(Vec x, std::vector<element::MembraneStrain>* strains) {
  constexpr PetscInt fields = 5;
  Vec natural = nullptr, root = nullptr;
  VecScatter to_root = nullptr;
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecCreateMPI(comm_, PETSC_DECIDE, fields * PetscInt(mesh_.triangle_count()), &natural));
  PetscCall(VecGetArrayRead(local_x_, &values));
  for (const LocalTriangle& t : triangles_) {
    const auto s =
        element::membrane_strain(t.material->membrane_model, t.material->membrane, t.rest,
                                 nonelastic[std::size_t(t.index)], gather<9>(values, t.dofs));
    const PetscScalar row[fields] = {s.warp, s.weft, s.shear, s.tension_warp, s.tension_weft};
    PetscInt rows[fields];
    for (PetscInt k = 0; k < fields; ++k)
      rows[k] = fields * t.index + k;
    PetscCall(VecSetValues(natural, fields, rows, row, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(VecAssemblyBegin(natural));
  PetscCall(VecAssemblyEnd(natural));
  PetscCall(VecScatterCreateToZero(natural, &to_root, &root));
  PetscCall(VecScatterBegin(to_root, natural, root, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_root, natural, root, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt size = 0;
  PetscCall(VecGetLocalSize(root, &size));
  strains->clear();
  PetscCall(VecGetArrayRead(root, &values));
  for (PetscInt t = 0; t < size / fields; ++t) {
    const PetscScalar* r = values + fields * t;
    strains->push_back({r[0], r[1], r[2], r[3], r[4]});
  }
  PetscCall(VecRestoreArrayRead(root, &values));
  PetscCall(VecScatterDestroy(&to_root));
  PetscCall(VecDestroy(&root));
  PetscCall(VecDestroy(&natural));
  PetscFunctionReturn(0);
}

std::vector<int> ClothProblem::owned_triangles() const {
  std::vector<int> owned;
  owned.reserve(triangles_.size());
  for (const LocalTriangle& t : triangles_)
    owned.push_back(t.index);
  return owned;
}

PetscErrorCode ClothProblem::visit_owned_triangles(Vec x, const TriangleVisitor& visit) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  for (const LocalTriangle& t : triangles_)
    visit(t.index, *t.material, t.rest, gather<9>(values, t.dofs));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::gather_anchors(std::vector<AnchorRow>* rows) {
  PetscFunctionBeginUser;
  const std::vector<double> local = contact_form_->anchor_rows();
  PetscMPIInt ranks = 1, rank = 0;
  PetscCallMPI(MPI_Comm_size(comm_, &ranks));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  const auto count = PetscMPIInt(local.size());
  std::vector<PetscMPIInt> counts(std::size_t(ranks), 0), offsets(std::size_t(ranks), 0);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_));
  for (std::size_t r = 1; r < counts.size(); ++r)
    offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(rank == 0 ? std::size_t(offsets.back() + counts.back()) : 0);
  PetscCallMPI(MPI_Gatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(),
                           offsets.data(), MPI_DOUBLE, 0, comm_));
  rows->clear();
  for (std::size_t i = 0; i + 10 <= all.size(); i += 10) {
    AnchorRow row;
    std::copy(all.begin() + long(i), all.begin() + long(i + 10), row.begin());
    rows->push_back(row);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::anchors_everywhere(std::vector<AnchorRow>* rows) {
  PetscFunctionBeginUser;
  PetscCall(gather_anchors(rows));
  auto count = static_cast<unsigned long>(rows->size());
  PetscCallMPI(MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, comm_));
  rows->resize(count);
  if (count > 0)
    PetscCallMPI(MPI_Bcast(rows->data()->data(),
                           PetscMPIInt(std::tuple_size<AnchorRow>::value * count), MPI_DOUBLE, 0,
                           comm_));
  PetscFunctionReturn(0);
}

void ClothProblem::restore_anchors(const std::vector<AnchorRow>& rows) {
  contact_form_->restore_anchors(rows);
}

PetscErrorCode ClothProblem::pin_reaction(Vec x, Eigen::Vector3d* reaction) {
  const PetscScalar* forces = nullptr;
  Vec f = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm_, &f));
  PetscCall(residual(x, f)); // fills local_f_ including the constrained dofs
  PetscCall(DMRestoreGlobalVector(dm_, &f));
  // Each triangle is assembled on one rank only, so summing every rank's
  // local contributions at the pinned dofs counts each exactly once. At
  // equilibrium the pin supplies R = grad E - f_ext there.
  double local[3] = {0.0, 0.0, 0.0};
  PetscCall(VecGetArrayRead(local_f_, &forces));
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    const PetscInt offset = vertex_dof_[std::size_t(pinned_[i])];
    if (offset < 0 || !holds(i)) continue;
    for (int d = 0; d < 3; ++d)
      local[d] += forces[offset + d];
  }
  PetscCall(VecRestoreArrayRead(local_f_, &forces));
  double total[3];
  PetscCallMPI(MPIU_Allreduce(local, total, 3, MPI_DOUBLE, MPI_SUM, comm_));
  *reaction = Eigen::Vector3d(total[0], total[1], total[2]);
  if (seam_form_) PetscCall(seam_form_->add_pin_reaction(x, reaction));
  PetscFunctionReturn(0);
}

} // namespace sartor
