// pkm.Exechon.drm_circle: the dependent rotational motion along a circle of tool points and its
// 5th-order fit, as `pkm exechon drm` (kinematics::sampleDrmCircle).
#include "exechon_drm_circle.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/exechon_drm.hpp"

namespace pkm::python {
namespace {

namespace kin = pkm::kinematics;

py::dict drmCircle(
    const Exechon& e, py::handle centre, double radius, double step_deg, py::handle direction) {
  kin::DrmCircleOptions opt;
  opt.centre = Eigen::Vector3d(vectorOf(centre, 3, "center").data());
  opt.direction = Eigen::Vector3d(vectorOf(direction, 3, "direction").data());
  opt.radius = radius;
  opt.step = degToRad(step_deg);
  std::string why;
  if (!opt.isValid(&why)) throw InvalidArgument(fmt::format("invalid circle: {}", why));
  kin::DrmCircleResult r;
  {
    py::gil_scoped_release release;
    kin::ExechonData data(e.machine->model);
    r = kin::sampleDrmCircle(e.machine->model, data, opt);
  }
  if (!r.ok())
    throw InvalidArgument(fmt::format("the circle leaves the workspace at point {} ({})",
                                      r.failed_index,
                                      kin::toString(r.status)));
  const auto m = static_cast<py::ssize_t>(r.theta.size());
  py::array_t<double> theta = newArray(m), phi = newArray(m), fit = newArray(m);
  for (py::ssize_t i = 0; i < m; ++i) {
    const auto k = static_cast<std::size_t>(i);
    theta.mutable_data()[i] = radToDeg(r.theta[k]);
    phi.mutable_data()[i] = radToDeg(r.phi[k]);
    fit.mutable_data()[i] = radToDeg(kin::evaluateDrmPolynomial(r.coefficients, r.theta[k]));
  }
  py::array_t<double> coefficients = newArray(6);
  std::copy(r.coefficients.begin(), r.coefficients.end(), coefficients.mutable_data());
  py::dict out;
  out["theta_deg"] = theta;
  out["phi_deg"] = phi;
  out["fit_deg"] = fit;
  out["coefficients"] = coefficients;
  out["max_abs_phi_deg"] = radToDeg(r.max_abs_phi);
  out["max_fit_deviation_deg"] = radToDeg(r.max_fit_deviation);
  return out;
}

}  // namespace

void defExechonDrmCircle(py::class_<Exechon>& cls) {
  cls.def("drm_circle",
          &drmCircle,
          py::arg("center"),
          py::arg("radius"),
          py::arg("step") = 1.0,
          py::arg("direction") = std::vector<double>{0.0, 0.0, -1.0},
          R"doc(Dependent rotational motion along a circle of tool points (as `pkm exechon drm`).

Parameters
----------
center : array_like, shape (3,)
    Circle centre (world frame, machine unit); the DRM reference.
radius : float
    Machine unit, > 0.
step : float, default 1
    Angle step, degrees.
direction : array_like, shape (3,), default (0, 0, -1)
    Tool direction = normal of the circle's plane.

Returns
-------
dict
    theta_deg, phi_deg, fit_deg (M,): the samples and the 5th-order fit, degrees;
    coefficients (6,): c0..c5 of phi(theta) with both in radians (seed 003 eq. 10);
    max_abs_phi_deg, max_fit_deviation_deg.

Raises
------
ValueError
    For an invalid circle or one that leaves the workspace.)doc");
}

}  // namespace pkm::python
