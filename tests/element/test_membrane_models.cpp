// The registry of membrane models (element/membrane_models.hpp): the
// built-in models under their names and indices, unknown names refused with
// the list of the known ones, and every model's reported tensions the
// derivatives of its energy density along the warp and weft.

#include "common/error.hpp"
#include "element/membrane.hpp"
#include "element/membrane_models.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace sartor::element {
namespace {

TEST(MembraneModels, TheBuiltInModelsAreRegisteredUnderTheirNames) {
  EXPECT_EQ(membrane_model_names(),
            (std::vector<std::string>{"baraff_witkin", "stvk", "measured"}));
  EXPECT_EQ(membrane_model_named("baraff_witkin", "test"), MembraneModel::baraff_witkin);
  EXPECT_EQ(membrane_model_named("stvk", "test"), MembraneModel::saint_venant_kirchhoff);
  EXPECT_EQ(membrane_model_named("measured", "test"), MembraneModel::measured);
  EXPECT_EQ(membrane_model_name(MembraneModel::saint_venant_kirchhoff), "stvk");
}

TEST(MembraneModels, AnUnknownNameIsRefusedWithTheKnownOnes) {
  try {
    membrane_model_named("neo_hookean", "option --membrane-model");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "option --membrane-model: unknown model 'neo_hookean' "
                                         "(baraff_witkin, stvk, measured)");
  }
}

// Along a pure warp stretch a = (s, 0, 0), b fixed across it, the warp
// tension a model reports is dW/ds, the force per width of the warp
// (T(s - 1) for Baraff-Witkin, S11 s for Saint Venant-Kirchhoff), computed
// here by central differences of the model's density.
TEST(MembraneModels, ReportedTensionsAreTheDensitysSlopes) {
  MembraneMaterial material{TensionCurve::linear(2000.0, "test"),
                            TensionCurve::linear(1500.0, "test"), 100.0, 0.2};
  for (MembraneModel model :
       {MembraneModel::baraff_witkin, MembraneModel::saint_venant_kirchhoff}) {
    const MembraneModelKernels& kernels = membrane_model_kernels(model);
    const Eigen::Vector3d b(0.0, 1.02, 0.0);
    const double stretch = 1.05, h = 1e-6;
    const auto energy = [&](double s) {
      return kernels.density(material, Eigen::Vector3d(s, 0.0, 0.0), b).energy;
    };
    const double slope = (energy(stretch + h) - energy(stretch - h)) / (2.0 * h); // dW/d|a|
    const double tension =
        kernels.tensions(material, Eigen::Vector3d(stretch, 0.0, 0.0), b).tension[0];
    EXPECT_NEAR(tension, slope, 1e-6 * std::abs(slope)) << membrane_model_name(model);
  }
}

} // namespace
} // namespace sartor::element
