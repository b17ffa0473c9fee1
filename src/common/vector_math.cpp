#include "common/vector_math.hpp"

#include <cmath>

namespace sartor {

void exp_of_negative(const double* x, double* out, std::size_t count) {
#pragma omp simd
  for (std::size_t i = 0; i < count; ++i)
    out[i] = std::exp(-x[i]);
}

} // namespace sartor
