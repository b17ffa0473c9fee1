// The files of fem/cloth_output and the OBJ writer as readers see them:
// units and ids as HDF5 attributes, clean series times, per-vertex vt and
// panel groups in OBJ files.
#include "fem/cloth_output.hpp"
#include "fem/h5_handle.hpp"
#include "mesh/generators.hpp"
#include "mesh/obj.hpp"

#include "tests/support/scratch_folder.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace sartor {
namespace {

namespace fs = std::filesystem;

const fs::path& scratch_folder() {
  return test_support::scratch_folder("sartor_output");
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

// The string attribute `name` of `object` (element `index` of an array).
std::string string_attribute(const std::string& file_path, const std::string& object,
                             const char* name, std::size_t index = 0) {
  const H5Handle file(H5Fopen(file_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  const H5Handle target(H5Oopen(file.get(), object.c_str(), H5P_DEFAULT), H5Oclose);
  const H5Handle attribute(H5Aopen(target.get(), name, H5P_DEFAULT), H5Aclose);
  if (attribute.get() < 0) return "(none)";
  const H5Handle type(H5Aget_type(attribute.get()), H5Tclose);
  const H5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const std::size_t width = H5Tget_size(type.get());
  const auto count = std::size_t(H5Sget_simple_extent_npoints(space.get()));
  std::string all(width * count, '\0');
  H5Aread(attribute.get(), type.get(), all.data());
  const std::string item = all.substr(index * width, width);
  return item.substr(0, item.find('\0'));
}

double read_scalar(const std::string& file_path, const std::string& set) {
  const H5Handle file(H5Fopen(file_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  const H5Handle data(H5Dopen2(file.get(), set.c_str(), H5P_DEFAULT), H5Dclose);
  double value = -1.0;
  H5Dread(data.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
  return value;
}

TEST(WriteObj, PairsVtWithVByLineAndStartsAGroupPerPanel) {
  // 2 x 1 squares, 4 triangles; the generator's uv is the vertex's (x, y).
  const TriangleMesh mesh = mesh::rectangle(2.0, 1.0, 2, 1);
  ASSERT_EQ(mesh.triangle_count(), 4u);
  const std::string path = (scratch_folder() / "groups.obj").string();
  write_obj(path, mesh, {"front", "front", "back", "back"});
  std::vector<std::string> vt, groups;
  for (const std::string& line : lines_of(path)) {
    if (line.rfind("vt ", 0) == 0) vt.push_back(line);
    if (line.rfind("g ", 0) == 0) groups.push_back(line);
  }
  ASSERT_EQ(vt.size(), mesh.vertex_count());
  for (std::size_t v = 0; v < vt.size(); ++v) {
    std::istringstream fields(vt[v].substr(3));
    double u = 0.0, w = 0.0;
    fields >> u >> w;
    EXPECT_EQ(u, mesh.positions[v].x()) << vt[v];
    EXPECT_EQ(w, mesh.positions[v].y()) << vt[v];
  }
  EXPECT_EQ(groups, (std::vector<std::string>{"g front", "g back"}));
}

TEST(ClothResults, CarryUnitsFabricAndPanelNames) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 2, 2);
  const std::vector<element::MembraneStrain> strains(mesh.triangle_count());
  ClothOutputLabels labels{{"silk"}, {"left", "right"}, {}};
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    labels.panel_of_triangle.push_back(t < mesh.triangle_count() / 2 ? 0 : 1);
  const std::string directory = (scratch_folder() / "result").string();
  write_cloth_results(directory, mesh, mesh.positions, strains, labels);
  const std::string h5 = directory + "/result.h5";
  EXPECT_EQ(string_attribute(h5, "/fields/position", "units"), "m");
  EXPECT_EQ(string_attribute(h5, "/cell_fields/tension_warp", "units"), "N/m");
  EXPECT_EQ(string_attribute(h5, "/cell_fields/strain_shear", "units"), "1");
  EXPECT_EQ(string_attribute(h5, "/mesh/material_uv", "units"), "m");
  EXPECT_EQ(string_attribute(h5, "/mesh/fabric_id", "names"), "silk");
  EXPECT_EQ(string_attribute(h5, "/mesh/panel_id", "names", 1), "right");
  std::vector<std::string> groups;
  for (const std::string& line : lines_of(directory + "/final.obj"))
    if (line.rfind("g ", 0) == 0) groups.push_back(line);
  EXPECT_EQ(groups, (std::vector<std::string>{"g left", "g right"}));
}

TEST(ClothTimeSeries, WritesTimesAccumulatedFromStepsAsMeant) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 1, 1);
  const std::vector<element::MembraneStrain> strains(mesh.triangle_count());
  const std::string directory = (scratch_folder() / "series").string();
  double time = 0.0;
  {
    ClothTimeSeries series(directory, mesh);
    for (int step = 0; step < 3; ++step)
      time += 0.1;
    series.write(time, mesh.positions, strains);
  }
  ASSERT_NE(time, 0.3); // 0.30000000000000004: the noise written before
  std::ifstream in(directory + "/series.xmf");
  const std::string xmf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(xmf.find("<Time Value=\"0.3\"/>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("Attribute Name=\"position\""), std::string::npos);
  EXPECT_EQ(read_scalar(directory + "/series.h5", "/steps/000000/time"), 0.3);
  EXPECT_EQ(string_attribute(directory + "/series.h5", "/steps/000000/time", "units"), "s");
}

} // namespace
} // namespace sartor
