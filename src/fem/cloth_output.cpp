#include "fem/cloth_output.hpp"

#include "common/error.hpp"
#include "common/output.hpp"
#include "mesh/obj.hpp"

#include <hdf5.h>

#include <cstdio>
#include <sstream>

namespace sartor {

namespace {

// Owns an HDF5 identifier.
class H5Handle {
public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

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

std::string xdmf_text(const std::string& h5, std::size_t vertices, std::size_t triangles) {
  std::ostringstream x;
  const auto item = [&](const std::string& set, std::size_t rows, int columns, const char* type) {
    std::ostringstream d;
    d << "<DataItem Dimensions=\"" << rows;
    if (columns > 1) d << " " << columns;
    d << "\" NumberType=\"" << type << "\" Precision=\"8\" Format=\"HDF\">" << h5 << ":" << set
      << "</DataItem>";
    return d.str();
  };
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"cloth\" GridType=\"Uniform\">\n"
    << "   <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << triangles << "\">"
    << item("/mesh/triangles", triangles, 3, "Int") << "</Topology>\n"
    << "   <Geometry GeometryType=\"XYZ\">" << item("/fields/position", vertices, 3, "Float")
    << "</Geometry>\n"
    << "   <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">"
    << item("/fields/displacement", vertices, 3, "Float") << "</Attribute>\n";
  for (const char* field :
       {"strain_warp", "strain_weft", "strain_shear", "tension_warp", "tension_weft"}) {
    x << "   <Attribute Name=\"" << field << "\" AttributeType=\"Scalar\" Center=\"Cell\">"
      << item(std::string("/cell_fields/") + field, triangles, 1, "Float") << "</Attribute>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return x.str();
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
    const std::size_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
    std::vector<long long> triangles;
    std::vector<double> uv, initial, current, displacement;
    for (const auto& t : mesh.triangles)
      triangles.insert(triangles.end(), {t[0], t[1], t[2]});
    for (const auto& corners : mesh.material_uv) {
      for (const auto& c : corners)
        uv.insert(uv.end(), {c[0], c[1]});
    }
    for (std::size_t v = 0; v < nv; ++v) {
      for (int d = 0; d < 3; ++d) {
        initial.push_back(mesh.positions[v][d]);
        current.push_back(positions[v][d]);
        displacement.push_back(positions[v][d] - mesh.positions[v][d]);
      }
    }
    write_dataset(file.get(), "/mesh/triangles", H5T_NATIVE_LLONG, triangles.data(), {nt, 3}, h5);
    write_dataset(file.get(), "/mesh/material_uv", H5T_NATIVE_DOUBLE, uv.data(), {nt, 3, 2}, h5);
    write_dataset(file.get(), "/mesh/initial_position", H5T_NATIVE_DOUBLE, initial.data(), {nv, 3},
                  h5);
    write_dataset(file.get(), "/fields/position", H5T_NATIVE_DOUBLE, current.data(), {nv, 3}, h5);
    write_dataset(file.get(), "/fields/displacement", H5T_NATIVE_DOUBLE, displacement.data(),
                  {nv, 3}, h5);
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
      write_dataset(file.get(), std::string("/cell_fields/") + name, H5T_NATIVE_DOUBLE,
                    values.data(), {nt}, h5);
    }
  }
  if (std::rename(temporary.c_str(), h5.c_str()) != 0) throw InputError(h5 + ": cannot write");
  write_file_atomically(directory + "/result.xmf",
                        xdmf_text("result.h5", mesh.vertex_count(), mesh.triangle_count()));
  TriangleMesh deformed = mesh;
  deformed.positions = positions;
  write_obj(directory + "/final.obj", deformed);
}

} // namespace sartor
