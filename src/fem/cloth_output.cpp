#include "fem/cloth_output.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/h5_handle.hpp"
#include "mesh/obj.hpp"

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace sartor {

namespace {

// A fixed-length string attribute `name` of the object at `object` in `file`:
// a scalar for one value, an array for several.
void write_string_attribute(hid_t file, const std::string& object, const char* name,
                            const std::vector<std::string>& values, const std::string& path) {
  std::size_t width = 1;
  for (const std::string& v : values)
    width = std::max(width, v.size());
  std::string packed;
  for (const std::string& v : values)
    packed += v + std::string(width - v.size(), '\0');
  const H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), width);
  const hsize_t count = values.size();
  const H5Handle space(
      values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), H5Sclose);
  const H5Handle target(H5Oopen(file, object.c_str(), H5P_DEFAULT), H5Oclose);
  const H5Handle attribute(
      H5Acreate2(target.get(), name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (attribute.get() < 0 || H5Awrite(attribute.get(), type.get(), packed.data()) < 0) {
    throw InputError(path + ": cannot write attribute " + name + " of " + object);
  }
}

// A dataset with its physical unit as the attribute `units` ("1": a ratio).
void write_dataset(hid_t file, const std::string& name, hid_t type, const void* data,
                   std::vector<hsize_t> dims, const char* units, const std::string& path) {
  {
    const H5Handle space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
    const H5Handle links(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
    H5Pset_create_intermediate_group(links.get(), 1);
    const H5Handle set(
        H5Dcreate2(file, name.c_str(), type, space.get(), links.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Dclose);
    if (set.get() < 0 || H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
      throw InputError(path + ": cannot write dataset " + name);
    }
  }
  write_string_attribute(file, name, "units", {units}, path);
}

// Per-triangle cell fields beside the strains, with their units.
struct CellFieldUnits {
  const char* name;
  const char* units;
};
constexpr CellFieldUnits membrane_fields[] = {{"strain_warp", "1"},
                                              {"strain_weft", "1"},
                                              {"strain_shear", "1"},
                                              {"tension_warp", "N/m"},
                                              {"tension_weft", "N/m"}};

// A time as written: 12 significant digits, so that a time accumulated from
// steps (0.09999999999999999) reads as the one meant (0.1).
double clean_time(double time) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", time);
  return std::strtod(text, nullptr);
}

// Panel ids are written when there is one per triangle (not when the
// solver refined the mesh the panels were numbered on).
bool has_panels(const TriangleMesh& mesh, const ClothOutputLabels& labels) {
  return !labels.panel_of_triangle.empty() &&
         labels.panel_of_triangle.size() == mesh.triangle_count();
}

std::string data_item(const std::string& h5, const std::string& set, std::size_t rows, int columns,
                      const char* type) {
  std::ostringstream d;
  d << "<DataItem Dimensions=\"" << rows;
  if (columns > 1) d << " " << columns;
  d << "\" NumberType=\"" << type << "\" Precision=\"8\" Format=\"HDF\">" << h5 << ":" << set
    << "</DataItem>";
  return d.str();
}

// One XDMF grid of the cloth whose datasets live under `group` of `h5`
// ("" for the final state: /fields, /cell_fields), at `time` when given
// (then also with the positions as a node field, see the header).
// The names of the extra cell fields in `group` (beyond the membrane's;
// none when it does not exist), sorted.
std::vector<std::string> cell_field_names(hid_t file, const std::string& group) {
  std::vector<std::string> names;
  if (H5Lexists(file, group.c_str(), H5P_DEFAULT) <= 0) return names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    const bool membrane =
        std::any_of(std::begin(membrane_fields), std::end(membrane_fields),
                    [&](const CellFieldUnits& f) { return f.name == std::string(name); });
    if (!membrane) static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  H5Literate_by_name(file, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names,
                     H5P_DEFAULT);
  return names;
}

std::string grid_text(const std::string& h5, const std::string& group, std::size_t vertices,
                      std::size_t triangles, bool has_panels, const double* time,
                      const std::vector<std::string>& extra_cell_fields = {},
                      const std::vector<std::string>& extra_node_fields = {}) {
  std::ostringstream x;
  const auto attribute = [&](const std::string& name, const char* kind, const char* center,
                             const std::string& item) {
    x << "   <Attribute Name=\"" << name << "\" AttributeType=\"" << kind << "\" Center=\""
      << center << "\">" << item << "</Attribute>\n";
  };
  x << "  <Grid Name=\"cloth\" GridType=\"Uniform\">\n";
  if (time) x << "   <Time Value=\"" << format_number(*time) << "\"/>\n";
  x << "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << triangles << "\">"
    << data_item(h5, "/mesh/triangles", triangles, 3, "Int") << "</Topology>\n"
    << "   <Geometry GeometryType=\"XYZ\">"
    << data_item(h5, group + "/fields/position", vertices, 3, "Float") << "</Geometry>\n";
  if (time) {
    attribute("position", "Vector", "Node",
              data_item(h5, group + "/fields/position", vertices, 3, "Float"));
  }
  attribute("displacement", "Vector", "Node",
            data_item(h5, group + "/fields/displacement", vertices, 3, "Float"));
  for (const std::string& field : extra_node_fields) {
    attribute(field, "Scalar", "Node",
              data_item(h5, group + "/fields/" + field, vertices, 1, "Float"));
  }
  std::vector<std::string> cell_fields;
  for (const CellFieldUnits& field : membrane_fields)
    cell_fields.push_back(field.name);
  cell_fields.insert(cell_fields.end(), extra_cell_fields.begin(), extra_cell_fields.end());
  for (const std::string& field : cell_fields) {
    attribute(field, "Scalar", "Cell",
              data_item(h5, group + "/cell_fields/" + field, triangles, 1, "Float"));
  }
  attribute("material_uv", "Matrix", "Cell",
            data_item(h5, "/mesh/material_uv", triangles, 6, "Float"));
  attribute("fabric_id", "Scalar", "Cell", data_item(h5, "/mesh/fabric_id", triangles, 1, "Int"));
  if (has_panels) {
    attribute("panel_id", "Scalar", "Cell", data_item(h5, "/mesh/panel_id", triangles, 1, "Int"));
  }
  x << "  </Grid>\n";
  return x.str();
}

// Positions, displacements and per-triangle strains under `group` of `file`.
void write_state(hid_t file, const std::string& group, const TriangleMesh& mesh,
                 const std::vector<Eigen::Vector3d>& positions,
                 const std::vector<element::MembraneStrain>& strains, const std::string& path) {
  const std::size_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
  if (positions.size() != nv || strains.size() != nt) {
    throw std::logic_error("write_state: positions or strains do not match the mesh");
  }
  std::vector<double> current, displacement;
  for (std::size_t v = 0; v < nv; ++v) {
    for (int d = 0; d < 3; ++d) {
      current.push_back(positions[v][d]);
      displacement.push_back(positions[v][d] - mesh.positions[v][d]);
    }
  }
  write_dataset(file, group + "/fields/position", H5T_NATIVE_DOUBLE, current.data(), {nv, 3}, "m",
                path);
  write_dataset(file, group + "/fields/displacement", H5T_NATIVE_DOUBLE, displacement.data(),
                {nv, 3}, "m", path);
  double element::MembraneStrain::*const members[] = {
      &element::MembraneStrain::warp, &element::MembraneStrain::weft,
      &element::MembraneStrain::shear, &element::MembraneStrain::tension_warp,
      &element::MembraneStrain::tension_weft};
  for (std::size_t f = 0; f < std::size(members); ++f) {
    std::vector<double> values;
    for (const auto& s : strains)
      values.push_back(s.*members[f]);
    write_dataset(file, group + "/cell_fields/" + membrane_fields[f].name, H5T_NATIVE_DOUBLE,
                  values.data(), {nt}, membrane_fields[f].units, path);
  }
}

// Per-triangle ids `ids` (all 0 when empty) as /mesh/NAME, with their names.
void write_ids(hid_t file, const std::string& name, const std::vector<int>& ids, std::size_t nt,
               const std::vector<std::string>& names, const std::string& path) {
  if (!ids.empty() && ids.size() != nt) {
    throw std::logic_error("write_ids: " + name + " does not have one id per triangle");
  }
  std::vector<long long> values(nt, 0);
  std::copy(ids.begin(), ids.end(), values.begin());
  write_dataset(file, "/mesh/" + name, H5T_NATIVE_LLONG, values.data(), {nt}, "1", path);
  if (!names.empty()) write_string_attribute(file, "/mesh/" + name, "names", names, path);
}

// The mesh: triangles, material uv (u, v of corner 0, 1, 2 in a row),
// initial positions, fabric and panel ids.
void write_mesh(hid_t file, const TriangleMesh& mesh, const ClothOutputLabels& labels,
                const std::string& path) {
  const std::size_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
  std::vector<long long> triangles;
  std::vector<double> uv, initial;
  for (const auto& t : mesh.triangles)
    triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  for (const auto& corners : mesh.material_uv) {
    for (const auto& c : corners)
      uv.insert(uv.end(), {c[0], c[1]});
  }
  for (const auto& p : mesh.positions)
    initial.insert(initial.end(), {p[0], p[1], p[2]});
  write_dataset(file, "/mesh/triangles", H5T_NATIVE_LLONG, triangles.data(), {nt, 3}, "1", path);
  write_dataset(file, "/mesh/material_uv", H5T_NATIVE_DOUBLE, uv.data(), {nt, 6}, "m", path);
  write_dataset(file, "/mesh/initial_position", H5T_NATIVE_DOUBLE, initial.data(), {nv, 3}, "m",
                path);
  write_ids(file, "fabric_id", mesh.material_ids, nt, labels.fabrics, path);
  if (has_panels(mesh, labels)) {
    write_ids(file, "panel_id", labels.panel_of_triangle, nt, labels.panels, path);
  }
}

std::string xdmf_document(const std::string& grids) {
  return "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n" + grids +
         " </Domain>\n</Xdmf>\n";
}

// The OBJ groups of `mesh`'s triangles: panel names, else fabric names.
std::vector<std::string> obj_groups(const TriangleMesh& mesh, const ClothOutputLabels& labels) {
  const bool panels = has_panels(mesh, labels);
  const std::vector<int>& ids = panels ? labels.panel_of_triangle : mesh.material_ids;
  const std::vector<std::string>& names = panels ? labels.panels : labels.fabrics;
  std::vector<std::string> groups;
  for (const int id : ids) {
    groups.push_back(std::size_t(id) < names.size()
                         ? names[std::size_t(id)]
                         : (panels ? "panel_" : "fabric_") + std::to_string(id));
  }
  return groups;
}

// series.h5 with the mesh and no states.
void create_series_file(const std::string& directory, const TriangleMesh& mesh,
                        const ClothOutputLabels& labels) {
  make_output_directory(directory);
  const std::string h5 = directory + "/series.h5";
  const H5Handle file(H5Fcreate(h5.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (file.get() < 0) throw InputError(h5 + ": cannot create HDF5 file");
  write_mesh(file.get(), mesh, labels, h5);
}

} // namespace

void write_cloth_results(const std::string& directory, const TriangleMesh& mesh,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<element::MembraneStrain>& strains,
                         const ClothOutputLabels& labels,
                         const std::vector<ClothNodeField>& node_fields) {
  make_output_directory(directory);
  std::vector<std::string> node_names;
  const std::string h5 = directory + "/result.h5";
  const std::string temporary = h5 + ".tmp";
  {
    const H5Handle file(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        H5Fclose);
    if (file.get() < 0) throw InputError(h5 + ": cannot create HDF5 file");
    write_mesh(file.get(), mesh, labels, h5);
    write_state(file.get(), "", mesh, positions, strains, h5);
    for (const ClothNodeField& field : node_fields) {
      if (field.values.size() != mesh.vertex_count()) {
        throw std::logic_error("write_cloth_results: node field " + field.name +
                               " does not have one value per vertex");
      }
      write_dataset(file.get(), "/fields/" + field.name, H5T_NATIVE_DOUBLE, field.values.data(),
                    {mesh.vertex_count()}, field.units.c_str(), h5);
      node_names.push_back(field.name);
    }
  }
  if (std::rename(temporary.c_str(), h5.c_str()) != 0) throw InputError(h5 + ": cannot write");
  write_file_atomically(
      directory + "/result.xmf",
      xdmf_document(grid_text("result.h5", "", mesh.vertex_count(), mesh.triangle_count(),
                              has_panels(mesh, labels), nullptr, {}, node_names)));
  TriangleMesh deformed = mesh;
  deformed.positions = positions;
  write_obj(directory + "/final.obj", deformed, obj_groups(mesh, labels));
}

ClothTimeSeries::ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh,
                                 const ClothOutputLabels& labels)
    : directory_(directory), mesh_(mesh), has_panels_(has_panels(mesh, labels)) {
  create_series_file(directory, mesh, labels);
}

ClothTimeSeries::ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh,
                                 const ClothOutputLabels& labels, double resumed_time)
    : directory_(directory), mesh_(mesh), has_panels_(has_panels(mesh, labels)) {
  // A resumed run writing into another folder starts its series there.
  const bool exists = std::ifstream(directory + "/series.h5").good();
  if (exists && keep_states(clean_time(resumed_time))) {
    write_index();
    return;
  }
  if (exists) {
    std::fprintf(stderr,
                 "sartor: warning: %s/series.h5 cannot be continued; it starts again with the "
                 "resumed states\n",
                 directory.c_str());
  }
  times_.clear();
  grids_.clear();
  extra_names_.clear();
  create_series_file(directory, mesh, labels);
}

bool ClothTimeSeries::keep_states(double last_time) {
  const std::string h5 = directory_ + "/series.h5";
  // HDF5 would print its own error stack for a damaged file.
  H5E_auto2_t handler = nullptr;
  void* handler_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &handler, &handler_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const H5Handle file(H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
  bool readable = file.get() >= 0 && H5Lexists(file.get(), "/mesh", H5P_DEFAULT) > 0;
  const bool has_steps = readable && H5Lexists(file.get(), "/steps", H5P_DEFAULT) > 0;
  for (std::size_t k = 0; has_steps && readable; ++k) {
    std::ostringstream group;
    group << "/steps/" << std::setw(6) << std::setfill('0') << k;
    if (H5Lexists(file.get(), group.str().c_str(), H5P_DEFAULT) <= 0) break;
    // A state after the checkpoint, or one a kill cut short, goes.
    double time = INFINITY;
    const std::string time_set = group.str() + "/time";
    if (H5Lexists(file.get(), time_set.c_str(), H5P_DEFAULT) > 0) {
      const H5Handle set(H5Dopen2(file.get(), time_set.c_str(), H5P_DEFAULT), H5Dclose);
      if (set.get() < 0 ||
          H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &time) < 0)
        time = INFINITY;
    }
    if (time > last_time) {
      readable = H5Ldelete(file.get(), group.str().c_str(), H5P_DEFAULT) >= 0;
      continue;
    }
    if (times_.empty()) extra_names_ = cell_field_names(file.get(), group.str() + "/cell_fields");
    times_.push_back(time);
    grids_ += grid_text("series.h5", group.str(), mesh_.vertex_count(), mesh_.triangle_count(),
                        has_panels_, &times_.back(), extra_names_);
  }
  H5Eset_auto2(H5E_DEFAULT, handler, handler_data);
  return readable;
}

void ClothTimeSeries::write(double time, const std::vector<Eigen::Vector3d>& positions,
                            const std::vector<element::MembraneStrain>& strains,
                            const std::vector<CellField>& extra_cell_fields) {
  const std::string h5 = directory_ + "/series.h5";
  std::ostringstream group;
  group << "/steps/" << std::setw(6) << std::setfill('0') << times_.size();
  std::vector<std::string> names;
  for (const CellField& field : extra_cell_fields)
    names.push_back(field.name);
  if (times_.empty()) extra_names_ = names;
  // A resumed series read its names back sorted.
  std::vector<std::string> sorted = names, sorted_extra = extra_names_;
  std::sort(sorted.begin(), sorted.end());
  std::sort(sorted_extra.begin(), sorted_extra.end());
  if (sorted != sorted_extra) {
    throw std::logic_error("ClothTimeSeries: every state must have the same cell fields");
  }
  const double written_time = clean_time(time);
  {
    const H5Handle file(H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
    if (file.get() < 0) throw InputError(h5 + ": cannot open HDF5 file for appending");
    write_state(file.get(), group.str(), mesh_, positions, strains, h5);
    for (const CellField& field : extra_cell_fields) {
      if (field.values.size() != mesh_.triangle_count()) {
        throw std::logic_error("ClothTimeSeries: cell field " + field.name +
                               " does not match the mesh");
      }
      write_dataset(file.get(), group.str() + "/cell_fields/" + field.name, H5T_NATIVE_DOUBLE,
                    field.values.data(), {field.values.size()}, field.units.c_str(), h5);
    }
    write_dataset(file.get(), group.str() + "/time", H5T_NATIVE_DOUBLE, &written_time, {1}, "s",
                  h5);
  }
  times_.push_back(written_time);
  grids_ += grid_text("series.h5", group.str(), mesh_.vertex_count(), mesh_.triangle_count(),
                      has_panels_, &times_.back(), extra_names_);
  // The index is rewritten whole, so rewriting it after every one of many
  // states would cost their number squared: after the first hundred states
  // it is rewritten at most once a second (and when the series closes).
  const auto now = std::chrono::steady_clock::now();
  if (times_.size() <= 100 || now - index_written_ >= std::chrono::seconds(1)) write_index();
}

void ClothTimeSeries::write_index() {
  write_file_atomically(directory_ + "/series.xmf",
                        xdmf_document(" <Grid Name=\"cloth\" GridType=\"Collection\" "
                                      "CollectionType=\"Temporal\">\n" +
                                      grids_ + " </Grid>\n"));
  index_states_ = times_.size();
  index_written_ = std::chrono::steady_clock::now();
}

ClothTimeSeries::~ClothTimeSeries() {
  if (index_states_ == times_.size()) return;
  try {
    write_index();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sartor: %s/series.xmf: %s\n", directory_.c_str(), error.what());
  }
}

} // namespace sartor
