#pragma once
// Elementwise math over arrays, vectorised (glibc's libmvec). This file's .cpp
// is the only one built with -ffast-math: an elementwise exp has nothing to
// reassociate, and libmvec's exp is accurate to a few ulp.

#include <cstddef>

namespace sartor {

// out[i] = exp(-x[i]); `out` may be `x`.
void exp_of_negative(const double* x, double* out, std::size_t count);

} // namespace sartor
