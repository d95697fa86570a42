// The one place the bindings turn core vectors into numpy arrays (and back).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "tessella/errors.h"
#include "tessella/vec.h"

namespace tessella::bindings {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// (N, D) float64 array of N points.
template <int D>
py::array_t<double> rows(const std::vector<Eigen::Matrix<double, D, 1>>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(D)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < D; ++k) m(i, k) = v[i][k];
  return a;
}

// N points from an (N, D) array; InvalidParameter naming `what` otherwise.
template <int D>
std::vector<Eigen::Matrix<double, D, 1>> points(const DoubleArray& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != D)
    throw InvalidParameter(std::string(what) + " must be an (N, " + std::to_string(D) +
                           ") array of points");
  auto r = a.unchecked<2>();
  std::vector<Eigen::Matrix<double, D, 1>> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int k = 0; k < D; ++k) out[i][k] = r(i, k);
  return out;
}

// 1-D arrays.
inline py::array_t<double> values(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}
inline py::array_t<bool> flags(const std::vector<bool>& v) {
  py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) r(i) = v[i];
  return a;
}
template <class T>
py::array_t<T> integers(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

}  // namespace tessella::bindings
