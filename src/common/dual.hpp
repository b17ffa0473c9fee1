#pragma once
// A forward-mode dual number: a value and its derivative with respect to one
// input. Code templated on the scalar type runs on double for values and on
// Dual for exact derivatives from the same source (the creep law's
// sensitivity to its end tension, for the monolithic coupling's tangent).
//
// Comparisons look at values only, so branches follow the value's path and
// the derivative is that of the branch taken.

#include <cmath>

namespace sartor {

struct Dual {
  double value = 0.0;
  double derivative = 0.0;

  Dual() = default;
  Dual(double v, double d = 0.0) : value(v), derivative(d) {} // NOLINT: constants promote
};

inline Dual operator+(Dual a, Dual b) {
  return {a.value + b.value, a.derivative + b.derivative};
}
inline Dual operator-(Dual a, Dual b) {
  return {a.value - b.value, a.derivative - b.derivative};
}
inline Dual operator-(Dual a) {
  return {-a.value, -a.derivative};
}
inline Dual operator*(Dual a, Dual b) {
  return {a.value * b.value, a.derivative * b.value + a.value * b.derivative};
}
inline Dual operator/(Dual a, Dual b) {
  return {a.value / b.value,
          (a.derivative * b.value - a.value * b.derivative) / (b.value * b.value)};
}
inline Dual& operator+=(Dual& a, Dual b) {
  return a = a + b;
}
inline Dual& operator-=(Dual& a, Dual b) {
  return a = a - b;
}
inline Dual& operator*=(Dual& a, Dual b) {
  return a = a * b;
}
inline Dual& operator/=(Dual& a, Dual b) {
  return a = a / b;
}

inline bool operator<(Dual a, Dual b) {
  return a.value < b.value;
}
inline bool operator>(Dual a, Dual b) {
  return a.value > b.value;
}
inline bool operator<=(Dual a, Dual b) {
  return a.value <= b.value;
}
inline bool operator>=(Dual a, Dual b) {
  return a.value >= b.value;
}
inline bool operator==(Dual a, Dual b) {
  return a.value == b.value;
}
inline bool operator!=(Dual a, Dual b) {
  return a.value != b.value;
}

inline Dual exp(Dual a) {
  const double e = std::exp(a.value);
  return {e, e * a.derivative};
}
inline Dual expm1(Dual a) {
  return {std::expm1(a.value), std::exp(a.value) * a.derivative};
}
inline Dual log1p(Dual a) {
  return {std::log1p(a.value), a.derivative / (1.0 + a.value)};
}
inline Dual sqrt(Dual a) {
  const double root = std::sqrt(a.value);
  return {root, 0.5 * a.derivative / root};
}
inline Dual abs(Dual a) {
  return a.value < 0.0 ? -a : a;
}

inline double value_of(double a) {
  return a;
}
inline double value_of(Dual a) {
  return a.value;
}

} // namespace sartor
