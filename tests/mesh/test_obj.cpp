// OBJ input and output: what the reader accepts, exact round trips of the
// generated meshes, and errors at FILE:LINE for the fixtures in data/.

#include "mesh/obj.hpp"

#include "common/error.hpp"
#include "mesh/generators.hpp"

#include "mesh_checks.hpp"

#include "tests/support/scratch_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>

namespace sartor {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) {
  return std::string(SARTOR_MESH_TEST_DATA_DIR) + "/" + name;
}

const fs::path& scratch_folder() {
  return test_support::scratch_folder("sartor_mesh_obj");
}

std::string scratch(const std::string& name) {
  return (scratch_folder() / name).string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void expect_identical(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.material_uv, b.material_uv);
}

TEST(ReadObj, PanelWithPolygonsRelativeIndicesAndExtras) {
  const auto m = read_obj(data("panel_cm.obj"), {0.01});
  ASSERT_EQ(m.vertex_count(), 5u);
  ASSERT_EQ(m.triangle_count(), 3u); // the quad as a fan of two, then the triangle
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (std::array<int, 3>{1, 4, 2}));
  EXPECT_EQ(m.positions[2], Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(m.positions[4], Eigen::Vector3d(2, 0.5, 0.25));
  EXPECT_EQ(m.material_uv[1][1], Eigen::Vector2d(0.01 * 20, 0.01 * 20));
  EXPECT_EQ(m.material_uv[2][1], Eigen::Vector2d(0.01 * 40, 0.01 * 10));
  EXPECT_TRUE(m.material_ids.empty());
  EXPECT_NEAR(test::total_material_area(m), 0.2 * 0.2 + 0.5 * 0.2 * 0.2, 1e-15);
  // Without the scale the numbers are taken as metres.
  EXPECT_EQ(read_obj(data("panel_cm.obj")).material_uv[2][1], Eigen::Vector2d(40, 10));
}

TEST(ReadObj, GivesEachTriangleItsGroup) {
  const std::string path = scratch("groups.obj");
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 2 0\nvt 2 1\n"
                         "f 1/1 2/2 3/3\ng front left\nf 2/2 5/5 6/6 3/3\ng back\nf 1/1 3/3 4/4\n";
  std::vector<std::string> groups{"stale"};
  const auto mesh = read_obj(path, {}, &groups);
  // The quad's fan gives two triangles of its group; a name's first word counts.
  EXPECT_EQ(groups, (std::vector<std::string>{"", "front", "front", "back"}));
  EXPECT_EQ(mesh.triangle_count(), groups.size());
}

TEST(ReadObj, RejectsABadUvScale) {
  for (const double scale : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity()}) {
    try {
      (void)read_obj(data("panel_cm.obj"), {scale});
      ADD_FAILURE() << scale;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("uv_scale must be a positive finite number"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(WriteObj, RoundTripsGeneratedMeshesExactly) {
  const std::vector<std::pair<std::string, TriangleMesh>> meshes{
      {"perturbed", mesh::rectangle(1.3, 0.7, 7, 5, mesh::RectanglePattern::perturbed)},
      {"disk", mesh::disk(0.35, 4)},
      {"band", mesh::cylinder_band(0.11, 0.3, 13, 4)},
      {"cap", mesh::sphere_cap(0.2, 1.1, 3)},
      {"refined_band", mesh::refine(mesh::cylinder_band(0.11, 0.3, 5, 2))},
  };
  for (const auto& [name, original] : meshes) {
    const std::string path = scratch(name + ".obj");
    write_obj(path, original);
    const auto back = read_obj(path);
    expect_identical(back, original);
    // Writing what was read gives the same file.
    write_obj(path + ".again", back);
    EXPECT_EQ(read_text(path + ".again"), read_text(path)) << name;
  }
}

TEST(WriteObj, WritesEachDistinctUvOnceAndNoTemporaryIsLeft) {
  const auto m = mesh::rectangle(1.0, 1.0, 4, 3);
  const std::string path = scratch("rectangle.obj");
  write_obj(path, m);
  const std::string text = read_text(path);
  std::size_t v = 0;
  std::size_t vt = 0;
  std::size_t f = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    v += line.rfind("v ", 0) == 0;
    vt += line.rfind("vt ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(v, 20u);
  EXPECT_EQ(vt, 20u);
  EXPECT_EQ(f, 24u);
  // The band has one more uv per row than vertices (the seam's far side).
  write_obj(path, mesh::cylinder_band(1.0, 1.0, 6, 2));
  std::istringstream band(read_text(path));
  vt = 0;
  for (std::string line; std::getline(band, line);)
    vt += line.rfind("vt ", 0) == 0;
  EXPECT_EQ(vt, 21u);
  for (const auto& entry : fs::directory_iterator(scratch_folder()))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

TEST(WriteObj, RefusesAnInvalidMesh) {
  auto m = mesh::rectangle(1.0, 1.0, 1, 1);
  m.positions[0].x() = std::numeric_limits<double>::quiet_NaN();
  const std::string path = scratch("invalid.obj");
  EXPECT_THROW(write_obj(path, m), InputError);
  EXPECT_FALSE(fs::exists(path));
}

struct ObjError {
  const char* file;
  int line; // 0: the message names no line
  const char* message;
};

void PrintTo(const ObjError& e, std::ostream* os) {
  *os << e.file;
}

class ReadObjError : public ::testing::TestWithParam<ObjError> {};

TEST_P(ReadObjError, NamesFileLineAndProblem) {
  const ObjError& expected = GetParam();
  const std::string path = data(expected.file);
  const std::string where =
      expected.line > 0 ? path + ":" + std::to_string(expected.line) + ": " : path + ": ";
  try {
    (void)read_obj(path);
    FAIL() << "read_obj accepted " << expected.file;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
    EXPECT_NE(message.find(expected.message), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, ReadObjError,
    ::testing::Values(
        ObjError{"index_zero.obj", 8, "vertex index 0 is invalid (OBJ indices start at 1)"},
        ObjError{"index_out_of_range.obj", 9,
                 "vertex index 9 is out of range (the file has 3 vertices)"},
        ObjError{"texture_out_of_range.obj", 7,
                 "texture coordinate index 7 is out of range (the file has 3 texture "
                 "coordinates)"},
        ObjError{"relative_before_first.obj", 7,
                 "relative vertex index -4 reaches before the first vertex (3 defined so far)"},
        ObjError{"missing_vt.obj", 5,
                 "face corner '1' has no texture coordinates; cloth meshes need vt for the rest "
                 "shape"},
        ObjError{"normals_without_vt.obj", 9, "face corner '1//1' has no texture coordinates"},
        ObjError{"nan_vertex.obj", 3, "vertex: 'nan' is not a finite number"},
        ObjError{"inf_texture.obj", 5, "texture coordinate: '-inf' is not a finite number"},
        ObjError{"too_few_vertices.obj", 7, "a face needs at least 3 corners, found 2"},
        ObjError{"garbage_statement.obj", 7, "unknown OBJ statement 'fce'"},
        ObjError{"bad_number.obj", 3, "vertex: '1.0.0' is not a number"},
        ObjError{"huge_number.obj", 2, "vertex: '1e400' is out of double range"},
        ObjError{"bad_index_token.obj", 7, "'b' is not a texture coordinate index"},
        ObjError{"vertex_two_values.obj", 2, "a vertex needs x y z"},
        ObjError{"repeated_vertex.obj", 8, "degenerate face: vertex 1 appears twice"},
        ObjError{"collinear_uv.obj", 7, "degenerate face: its texture coordinates are collinear"},
        ObjError{"nonconvex.obj", 10, "fan from its first corner folds over"},
        ObjError{"no_faces.obj", 0, "the file has no faces"},
        ObjError{"does_not_exist.obj", 0, "cannot open file"}));

} // namespace
} // namespace sartor
