#pragma once
// Eigen matrices of dual numbers (common/dual.hpp): Eigen's traits for the
// scalar, so that code templated on it runs its Eigen arithmetic on double
// for values and on Dual for their exact derivative along one direction.
// Dual and double mix in expressions (a double is a constant). Eigen's
// decompositions are not meant for Dual: differentiate a solve by hand
// (values() and derivatives() split a matrix).

#include "common/dual.hpp"

#include <Eigen/Core>

#include <limits>

namespace Eigen {

template <>
struct NumTraits<sartor::Dual> : GenericNumTraits<double> {
  using Real = sartor::Dual;
  using NonInteger = sartor::Dual;
  using Nested = sartor::Dual;
  using Literal = sartor::Dual;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 2,
    AddCost = 2,
    MulCost = 3
  };
  static Real epsilon() { return std::numeric_limits<double>::epsilon(); }
  static Real dummy_precision() { return NumTraits<double>::dummy_precision(); }
  static Real highest() { return std::numeric_limits<double>::max(); }
  static Real lowest() { return std::numeric_limits<double>::lowest(); }
  static int digits10() { return std::numeric_limits<double>::digits10; }
};

template <typename BinaryOp>
struct ScalarBinaryOpTraits<sartor::Dual, double, BinaryOp> {
  using ReturnType = sartor::Dual;
};
template <typename BinaryOp>
struct ScalarBinaryOpTraits<double, sartor::Dual, BinaryOp> {
  using ReturnType = sartor::Dual;
};

} // namespace Eigen

namespace sartor {

// The values and the derivatives of a matrix of dual numbers.
template <typename Derived>
auto values(const Eigen::MatrixBase<Derived>& m) {
  return m.unaryExpr([](const Dual& d) { return d.value; }).eval();
}
template <typename Derived>
auto derivatives(const Eigen::MatrixBase<Derived>& m) {
  return m.unaryExpr([](const Dual& d) { return d.derivative; }).eval();
}

} // namespace sartor
