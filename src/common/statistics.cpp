#include "common/statistics.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <stdexcept>

namespace sartor {

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::domain_error("normal_quantile: p must lie in (0, 1)");
  return boost::math::quantile(boost::math::normal_distribution<double>(), p);
}

double student_t_quantile(double p, double dof) {
  if (!(dof > 0.0)) throw std::domain_error("student_t_quantile: dof must be > 0");
  if (!(p > 0.0 && p < 1.0)) throw std::domain_error("student_t_quantile: p must lie in (0, 1)");
  return boost::math::quantile(boost::math::students_t_distribution<double>(dof), p);
}

} // namespace sartor
