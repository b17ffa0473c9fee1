#pragma once
// Forward-mode derivatives along one direction by Eigen's AutoDiffScalar.
// Code templated on the scalar runs on double for values and on AutoDiff for
// their exact derivative from the same source: the creep law's sensitivity
// to its end tension (the monolithic coupling's tangent), the bending rest
// data's change along a change of the pattern (the design sensitivity).
// Comparisons look at values only, so branches follow the value's path and
// the derivative is that of the branch taken. It replaced a dual number of
// our own, which was no faster (docs/benchmarks.md).
//
// Eigen's arithmetic builds expression types (AutoDiffScalar<CwiseBinaryOp
// ...>) that template argument deduction does not convert: name the scalar
// (f<S>(a * b)) where a template takes an expression. Such an expression may
// refer to its operands: convert it to AutoDiff before they go. Eigen's
// decompositions are not meant for it: differentiate a solve by hand
// (values() and derivatives() split a matrix).

#include <Eigen/Core>
// After Eigen/Core: the AutoDiff module does not include it.
#include <unsupported/Eigen/AutoDiff>

#include <cmath>

namespace sartor {

using AutoDiff = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;

// A value that moves by `derivative` along the direction differentiated.
inline AutoDiff seeded(double value, double derivative) {
  return AutoDiff(value, Eigen::Matrix<double, 1, 1>::Constant(derivative));
}

inline double value_of(double a) {
  return a;
}
inline double value_of(const AutoDiff& a) {
  return a.value();
}
inline double derivative_of(const AutoDiff& a) {
  return a.derivatives()(0);
}

// The values and the derivatives of a matrix of AutoDiff.
template <typename Derived>
auto values(const Eigen::MatrixBase<Derived>& m) {
  return m.unaryExpr([](const AutoDiff& a) { return a.value(); }).eval();
}
template <typename Derived>
auto derivatives(const Eigen::MatrixBase<Derived>& m) {
  return m.unaryExpr([](const AutoDiff& a) { return derivative_of(a); }).eval();
}

} // namespace sartor

namespace Eigen {

// Eigen 3.4's AutoDiff module (Debian 12) lacks expm1 and log1p, which the
// creep law needs for their precision near zero. In namespace Eigen, as its
// exp and log, for argument-dependent lookup.
template <typename DerType>
auto expm1(const AutoDiffScalar<DerType>& x) {
  return MakeAutoDiffScalar(std::expm1(x.value()), x.derivatives() * std::exp(x.value()));
}
template <typename DerType>
auto log1p(const AutoDiffScalar<DerType>& x) {
  return MakeAutoDiffScalar(std::log1p(x.value()), x.derivatives() / (1.0 + x.value()));
}

} // namespace Eigen
