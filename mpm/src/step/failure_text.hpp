#pragma once
// Vectors and matrices in numerical-failure diagnostics.
#include <sstream>
#include <string>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// A scalar with six significant digits (std::to_string prints a 1e-8 s step as 0.000000).
inline std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

template <int D>
std::string format_vector(const Vec<D>& v) {
  std::ostringstream out;
  out.precision(6);
  out << "(";
  for (int k = 0; k < D; ++k) out << (k ? ", " : "") << v[k];
  out << ")";
  return out.str();
}

template <int D>
std::string format_matrix(const Mat<D>& m) {
  std::ostringstream out;
  out.precision(6);
  out << "[";
  for (int i = 0; i < D; ++i) {
    out << (i ? "; " : "");
    for (int j = 0; j < D; ++j) out << (j ? " " : "") << m(i, j);
  }
  out << "]";
  return out.str();
}

}  // namespace fragmpm::mpm
