#include "fem/cloth_output.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/h5_handle.hpp"
#include "mesh/obj.hpp"

#include <hdf5.h>

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace sartor {

namespace {

void write_dataset(hid_t file, const std::string& name, hid_t type, const void* data,
                   std::vector<hsize_t> dims, const std::string& path) {
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

// One XDMF grid of the cloth whose datasets live under `group` of `h5`
// ("" for the final state: /fields, /cell_fields), at `time` when given.
std::string grid_text(const std::string& h5, const std::string& group, const std::string& name,
                      std::size_t vertices, std::size_t triangles, const double* time,
                      const std::vector<std::string>& extra_cell_fields = {}) {
  std::ostringstream x;
  const auto item = [&](const std::string& set, std::size_t rows, int columns, const char* type) {
    std::ostringstream d;
    d << "<DataItem Dimensions=\"" << rows;
    if (columns > 1) d << " " << columns;
    d << "\" NumberType=\"" << type << "\" Precision=\"8\" Format=\"HDF\">" << h5 << ":" << set
      << "</DataItem>";
    return d.str();
  };
  x << "  <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n";
  if (time) x << "   <Time Value=\"" << format_number(*time) << "\"/>\n";
  x << "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << triangles << "\">"
    << item("/mesh/triangles", triangles, 3, "Int") << "</Topology>\n"
    << "   <Geometry GeometryType=\"XYZ\">"
    << item(group + "/fields/position", vertices, 3, "Float") << "</Geometry>\n"
    << "   <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">"
    << item(group + "/fields/displacement", vertices, 3, "Float") << "</Attribute>\n";
  std::vector<std::string> cell_fields{"strain_warp", "strain_weft", "strain_shear", "tension_warp",
                                       "tension_weft"};
  cell_fields.insert(cell_fields.end(), extra_cell_fields.begin(), extra_cell_fields.end());
  for (const std::string& field : cell_fields) {
    x << "   <Attribute Name=\"" << field << "\" AttributeType=\"Scalar\" Center=\"Cell\">"
      << item(group + "/cell_fields/" + field, triangles, 1, "Float") << "</Attribute>\n";
  }
  x << "  </Grid>\n";
  return x.str();
}

std::string xdmf_text(const std::string& h5, std::size_t vertices, std::size_t triangles) {
  return "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n" +
         grid_text(h5, "", "cloth", vertices, triangles, nullptr) + " </Domain>\n</Xdmf>\n";
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
  write_dataset(file, group + "/fields/position", H5T_NATIVE_DOUBLE, current.data(), {nv, 3}, path);
  write_dataset(file, group + "/fields/displacement", H5T_NATIVE_DOUBLE, displacement.data(),
                {nv, 3}, path);
  const std::pair<const char*, double element::MembraneStrain::*> fields[] = {
      {"strain_warp", &element::MembraneStrain::warp},
      {"strain_weft", &element::MembraneStrain::weft},
      {"strain_shear", &element::MembraneStrain::shear},
      {"tension_warp", &element::MembraneStrain::tension_warp},
      {"tension_weft", &element::MembraneStrain::tension_weft}};
  for (const auto& [name, member] : fields) {
    std::vector<double> values;
    for (const auto& s : strains)
      values.push_back(s.*member);
    write_dataset(file, group + "/cell_fields/" + name, H5T_NATIVE_DOUBLE, values.data(), {nt},
                  path);
  }
}

// The mesh: triangles, material uv and initial positions.
void write_mesh(hid_t file, const TriangleMesh& mesh, const std::string& path) {
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
  write_dataset(file, "/mesh/triangles", H5T_NATIVE_LLONG, triangles.data(), {nt, 3}, path);
  write_dataset(file, "/mesh/material_uv", H5T_NATIVE_DOUBLE, uv.data(), {nt, 3, 2}, path);
  write_dataset(file, "/mesh/initial_position", H5T_NATIVE_DOUBLE, initial.data(), {nv, 3}, path);
}

} // namespace

void write_cloth_results(const std::string& directory, const TriangleMesh& mesh,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<element::MembraneStrain>& strains) {
  make_output_directory(directory);
  const std::string h5 = directory + "/result.h5";
  const std::string temporary = h5 + ".tmp";
  {
    const H5Handle file(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        H5Fclose);
    if (file.get() < 0) throw InputError(h5 + ": cannot create HDF5 file");
    write_mesh(file.get(), mesh, h5);
    write_state(file.get(), "", mesh, positions, strains, h5);
  }
  if (std::rename(temporary.c_str(), h5.c_str()) != 0) throw InputError(h5 + ": cannot write");
  write_file_atomically(directory + "/result.xmf",
                        xdmf_text("result.h5", mesh.vertex_count(), mesh.triangle_count()));
  TriangleMesh deformed = mesh;
  deformed.positions = positions;
  write_obj(directory + "/final.obj", deformed);
}

ClothTimeSeries::ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh)
    : directory_(directory), mesh_(mesh) {
  make_output_directory(directory);
  const std::string h5 = directory + "/series.h5";
  const H5Handle file(H5Fcreate(h5.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (file.get() < 0) throw InputError(h5 + ": cannot create HDF5 file");
  write_mesh(file.get(), mesh, h5);
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
  if (names != extra_names_) {
    throw std::logic_error("ClothTimeSeries: every state must have the same cell fields");
  }
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
                    field.values.data(), {field.values.size()}, h5);
    }
    write_dataset(file.get(), group.str() + "/time", H5T_NATIVE_DOUBLE, &time, {1}, h5);
  }
  times_.push_back(time);
  grids_ += grid_text("series.h5", group.str(), "cloth", mesh_.vertex_count(),
                      mesh_.triangle_count(), &times_.back(), extra_names_);
  // The index is rewritten whole, so rewriting it after every one of many
  // states would cost their number squared: after the first hundred states
  // it is rewritten at most once a second (and when the series closes).
  const auto now = std::chrono::steady_clock::now();
  if (times_.size() <= 100 || now - index_written_ >= std::chrono::seconds(1)) write_index();
}

void ClothTimeSeries::write_index() {
  write_file_atomically(directory_ + "/series.xmf",
                        "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
                        " <Grid Name=\"cloth\" GridType=\"Collection\" "
                        "CollectionType=\"Temporal\">\n" +
                            grids_ + " </Grid>\n </Domain>\n</Xdmf>\n");
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
