// Body OBJ reading and checking: a good file, and one malformed file per
// rule, each rejected with FILE:LINE and what is wrong.

#include "common/error.hpp"
#include "contact/body_obj.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <string>

namespace {

std::string data(const std::string& name) {
  return std::string(SARTOR_BODY_TEST_DATA_DIR) + "/" + name;
}

std::string error_of(const std::string& name) {
  try {
    sartor::read_body_obj(data(name));
  } catch (const sartor::InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(BodyObj, CubeWithQuadsIsAClosedBody) {
  const sartor::BodyMesh cube = sartor::read_body_obj(data("cube.obj"));
  ASSERT_EQ(cube.faces.size(), 12u);
  const sartor::BodyMeasures m = sartor::measure_body(cube);
  EXPECT_NEAR(m.volume, 1.0, 1e-14);
  EXPECT_NEAR(m.area, 6.0, 1e-14);
  EXPECT_EQ(m.components, 1u);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_EQ(m.edges, 18u);
  EXPECT_DOUBLE_EQ(m.upper.z() - m.lower.z(), 1.0);
}

struct Malformed {
  const char* file;
  const char* message; // must appear in the error, after "DATA/"
};

// Names the case in test listings (instead of its bytes).
void PrintTo(const Malformed& malformed, std::ostream* out) {
  *out << malformed.file;
}

class MalformedBodyObj : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedBodyObj, IsRejectedWithFileLineAndReason) {
  const std::string error = error_of(GetParam().file);
  EXPECT_NE(error.find(data(GetParam().message)), std::string::npos) << error;
}

INSTANTIATE_TEST_SUITE_P(
    Rules, MalformedBodyObj,
    ::testing::Values(
        Malformed{"bad_index.obj",
                  "bad_index.obj:9: vertex index 9 is out of range (the mesh has 4 vertices)"},
        Malformed{"nan_vertex.obj", "nan_vertex.obj:3: vertex coordinate 'nan' is not a finite"},
        Malformed{"degenerate.obj",
                  "degenerate.obj:11: degenerate face (vertices 1 2 5): its corners are collinear"},
        Malformed{"nonmanifold_edge.obj",
                  "nonmanifold_edge.obj:7: non-manifold edge (1, 2): shared by 3 faces"},
        Malformed{"open.obj", "open.obj:6: the mesh is not closed"},
        Malformed{"inconsistent.obj", "inconsistent.obj:6: inconsistent orientation"},
        Malformed{"inward.obj", "inward.obj:6: the closed surface this face belongs to encloses "
                                "a negative volume"},
        Malformed{"empty.obj", "empty.obj: the body has no faces"},
        Malformed{"unknown_statement.obj",
                  "unknown_statement.obj:6: unknown OBJ statement 'cstype'"},
        Malformed{"nonmanifold_vertex.obj",
                  "nonmanifold_vertex.obj:10: non-manifold vertex 4: its 6 faces form more than "
                  "one fan"},
        Malformed{"self_intersecting.obj", "self_intersecting.obj:14: the surface intersects "
                                           "itself: this face crosses another ("}),
    [](const ::testing::TestParamInfo<Malformed>& param) {
      std::string name = param.param.file;
      return name.substr(0, name.find('.'));
    });

TEST(BodyObj, InMemoryMeshesAreCheckedWithZeroBasedNames) {
  sartor::BodyMesh open_tetrahedron{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                    {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}}};
  try {
    sartor::check_body_mesh(open_tetrahedron, "generator");
    FAIL() << "an open mesh passed";
  } catch (const sartor::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("generator: face 0: the mesh is not closed"),
              std::string::npos)
        << error.what();
  }
  open_tetrahedron.faces.push_back({1, 2, 3});
  EXPECT_NO_THROW(sartor::check_body_mesh(open_tetrahedron, "generator"));
}

} // namespace
