#include "fem/bending_models.hpp"

#include "common/error.hpp"

namespace sartor::fem {

namespace {

// Every bending model, one line each, in the order of BendingModel's
// indices: the built-in ones first, as BendingModel names them.
std::vector<BendingModelEntry> register_bending_models() {
  return {
      discrete_shell_model(),
      quadratic_model(),
      patch_model(),
  };
}

const std::vector<BendingModelEntry>& registry() {
  static const std::vector<BendingModelEntry> models = register_bending_models();
  return models;
}

} // namespace

const BendingModelEntry& bending_model_entry(element::BendingModel model) {
  return registry().at(std::size_t(model.index()));
}

element::BendingModel bending_model_named(const std::string& name, const std::string& context) {
  const std::vector<BendingModelEntry>& models = registry();
  std::string names;
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (models[i].name == name) return element::BendingModel(int(i));
    names += (i ? ", " : "") + models[i].name;
  }
  throw InputError(context + ": unknown model '" + name + "' (" + names + ")");
}

const std::string& bending_model_name(element::BendingModel model) {
  return bending_model_entry(model).name;
}

std::vector<std::string> bending_model_names() {
  std::vector<std::string> names;
  for (const BendingModelEntry& model : registry())
    names.push_back(model.name);
  return names;
}

} // namespace sartor::fem
