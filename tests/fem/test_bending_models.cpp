// The registry of bending models (fem/bending_models.hpp): names, lookup,
// the error for an unknown name, and what each built-in model declares.

#include "common/error.hpp"
#include "fem/bending_models.hpp"

#include <gtest/gtest.h>

namespace sartor {
namespace {

TEST(BendingModels, NamesAreRegisteredInTheOrderOfTheirIndices) {
  const std::vector<std::string> expected{"discrete_shell", "quadratic", "patch"};
  EXPECT_EQ(fem::bending_model_names(), expected);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const element::BendingModel model = fem::bending_model_named(expected[i], "test");
    EXPECT_EQ(model.index(), int(i));
    EXPECT_EQ(fem::bending_model_name(model), expected[i]);
    EXPECT_NE(fem::bending_model_entry(model).form, nullptr) << expected[i];
    EXPECT_FALSE(fem::bending_model_entry(model).summary.empty()) << expected[i];
  }
  EXPECT_EQ(fem::bending_model_name(element::BendingModel::discrete_shell), "discrete_shell");
  EXPECT_EQ(fem::bending_model_name(element::BendingModel::quadratic), "quadratic");
  EXPECT_EQ(fem::bending_model_name(element::BendingModel::patch), "patch");
}

TEST(BendingModels, AnUnknownNameIsRefusedWithTheRegisteredNames) {
  try {
    fem::bending_model_named("plate", "option --bending-model");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "option --bending-model: unknown model 'plate' "
                           "(discrete_shell, quadratic, patch)");
  }
}

TEST(BendingModels, OnlyTheDiscreteShellCarriesCreaseAngles) {
  EXPECT_TRUE(
      fem::bending_model_entry(element::BendingModel::discrete_shell).carries_crease_angles);
  EXPECT_FALSE(fem::bending_model_entry(element::BendingModel::quadratic).carries_crease_angles);
  EXPECT_FALSE(fem::bending_model_entry(element::BendingModel::patch).carries_crease_angles);
}

} // namespace
} // namespace sartor
