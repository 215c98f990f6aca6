// pcr._pcr: the compiled part of the Python package pcr (python/pcr/__init__.py re-exports it).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "pcr/core/error.hpp"

PYBIND11_MODULE(_pcr, m) {
  m.doc() = "pcr: parallel continuum robots by isogeometric collocation (C++ core)";
  // InputError carries the C++ message unchanged (file, line, element, value where there is one).
  pybind11::register_exception<pcr::InputError>(m, "InputError", PyExc_ValueError);
  pcr::python::bind_model(m);
  pcr::python::bind_results(m);
  pcr::python::bind_kinematics(m);
}
