#pragma once
// An entry of a registry of models (membrane, bending) by its place in the
// registry: cheap to copy and compare, with the built-in models as named
// constants of the derived class (MembraneModel::measured). The derived
// class inherits the constructors:
//     class BendingModel : public RegistryIndex<BendingModel> {
//       using RegistryIndex::RegistryIndex; ... };

namespace sartor {

template <class Model>
class RegistryIndex {
public:
  constexpr RegistryIndex() = default;
  constexpr explicit RegistryIndex(int index) : index_(index) {}
  constexpr int index() const { return index_; }
  friend constexpr bool operator==(Model a, Model b) { return a.index() == b.index(); }
  friend constexpr bool operator!=(Model a, Model b) { return !(a == b); }

private:
  int index_ = 0;
};

} // namespace sartor
