#include "element/membrane_models.hpp"

#include "common/error.hpp"

#include <vector>

namespace sartor::element {

namespace {

// A column of F_e shorter than this has no direction (BW model).
constexpr double min_stretch = 1e-12;

// Every membrane model, one line each, in the order of MembraneModel's
// indices: the built-in ones first, as MembraneModel names them.
std::vector<MembraneModelKernels> register_membrane_models() {
  return {
      baraff_witkin_model(),
      saint_venant_kirchhoff_model(),
      measured_model(),
  };
}

const std::vector<MembraneModelKernels>& registry() {
  static const std::vector<MembraneModelKernels> models = register_membrane_models();
  return models;
}

} // namespace

const MembraneModelKernels& membrane_model_kernels(MembraneModel model) {
  return registry()[std::size_t(model.index())];
}

MembraneModel membrane_model_named(const std::string& name, const std::string& context) {
  const std::vector<MembraneModelKernels>& models = registry();
  std::string names;
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (models[i].name == name) return MembraneModel(int(i));
    names += (i ? ", " : "") + models[i].name;
  }
  throw InputError(context + ": unknown model '" + name + "' (" + names + ")");
}

const std::string& membrane_model_name(MembraneModel model) {
  return membrane_model_kernels(model).name;
}

std::vector<std::string> membrane_model_names() {
  std::vector<std::string> names;
  for (const MembraneModelKernels& model : registry())
    names.push_back(model.name);
  return names;
}

Stretch stretch_of(const Vector3d& v) {
  Stretch s;
  s.length = v.norm();
  if (s.length < min_stretch) return s;
  s.unit = v / s.length;
  s.hessian = (Matrix3d::Identity() - s.unit * s.unit.transpose()) / s.length;
  return s;
}

double coupling_modulus(const MembraneMaterial& material) {
  return material.poisson *
         std::sqrt(material.warp.initial_modulus() * material.weft.initial_modulus());
}

} // namespace sartor::element
