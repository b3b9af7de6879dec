// pkm.Hexapod's geometry: the joint centres, length offsets, stroke, tool offset and home as
// arrays, and with_geometry (a new machine with some of them replaced).
#include "hexapod_geometry.hpp"

#include <fmt/format.h>

#include <memory>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"

namespace pkm::python {
namespace {

namespace kin = pkm::kinematics;

/// (6, 3) array of a per-strut vector.
py::array_t<double> strutVectors(const Hexapod& h, Eigen::Vector3d kin::Strut::*field) {
  py::array_t<double> a = newArray(6, 3);
  for (int i = 0; i < kin::kStruts; ++i)
    for (int k = 0; k < 3; ++k)
      a.mutable_data()[3 * i + k] =
          (h.machine->model.struts[static_cast<std::size_t>(i)].*field)[k];
  return a;
}

Hexapod withGeometry(const Hexapod& h,
                     py::handle base,
                     py::handle platform,
                     py::handle offsets,
                     py::handle stroke,
                     py::handle tool_offset) {
  auto m = std::make_shared<io::HexapodMachine>(*h.machine);
  if (!base.is_none()) {
    const DoubleArray b = rowsOf(base, 3, "base_joints", false);
    if (b.shape(0) != 6) throw InvalidArgument("base_joints: expected shape (6, 3)");
    for (std::size_t i = 0; i < 6; ++i)
      m->model.struts[i].world_p_base = Eigen::Vector3d(b.data() + 3 * i);
  }
  if (!platform.is_none()) {
    const DoubleArray p = rowsOf(platform, 3, "platform_joints", false);
    if (p.shape(0) != 6) throw InvalidArgument("platform_joints: expected shape (6, 3)");
    for (std::size_t i = 0; i < 6; ++i)
      m->model.struts[i].platform_p_joint = Eigen::Vector3d(p.data() + 3 * i);
  }
  if (!offsets.is_none()) {
    const DoubleArray o = vectorOf(offsets, 6, "length_offsets");
    for (std::size_t i = 0; i < 6; ++i) m->model.struts[i].length_offset = o.data()[i];
  }
  if (!stroke.is_none()) {
    const DoubleArray s = rowsOf(stroke, 2, "stroke", false);
    if (s.shape(0) != 6) throw InvalidArgument("stroke: expected shape (6, 2)");
    for (std::size_t i = 0; i < 6; ++i) {
      m->model.struts[i].min_reading = s.data()[2 * i];
      m->model.struts[i].max_reading = s.data()[2 * i + 1];
    }
  }
  if (!tool_offset.is_none())
    m->model.tool_offset = Eigen::Vector3d(vectorOf(tool_offset, 3, "tool_offset").data());
  m->model.validate();
  m->source = fmt::format("{} (geometry changed)", h.machine->source);
  return Hexapod{std::move(m)};
}

}  // namespace

void defHexapodGeometry(py::class_<Hexapod>& cls) {
  cls.def_property_readonly(
         "base_joints",
         [](const Hexapod& h) { return strutVectors(h, &kin::Strut::world_p_base); },
         "(6, 3) base joint centres b_i, world frame, machine unit.")
      .def_property_readonly(
          "platform_joints",
          [](const Hexapod& h) { return strutVectors(h, &kin::Strut::platform_p_joint); },
          "(6, 3) platform joint centres a_i, platform frame, machine unit.")
      .def_property_readonly(
          "length_offsets",
          [](const Hexapod& h) {
            py::array_t<double> a = newArray(6);
            for (std::size_t i = 0; i < 6; ++i)
              a.mutable_data()[i] = h.machine->model.struts[i].length_offset;
            return a;
          },
          "(6,) reading + offset = joint-centre distance, machine unit.")
      .def_property_readonly(
          "stroke",
          [](const Hexapod& h) {
            py::array_t<double> a = newArray(6, 2);
            for (std::size_t i = 0; i < 6; ++i) {
              a.mutable_data()[2 * i] = h.machine->model.struts[i].min_reading;
              a.mutable_data()[2 * i + 1] = h.machine->model.struts[i].max_reading;
            }
            return a;
          },
          "(6, 2) lowest and highest strut reading, machine unit (+-inf: no limit).")
      .def_property_readonly(
          "tool_offset",
          [](const Hexapod& h) {
            py::array_t<double> a = newArray(3);
            Eigen::Map<Eigen::Vector3d>(a.mutable_data()) = h.machine->model.tool_offset;
            return a;
          },
          "(3,) TCP in the platform frame, machine unit.")
      .def_property_readonly(
          "home",
          [](const Hexapod& h) {
            py::array_t<double> a = newArray(6);
            const kin::PoseRpy& p = h.machine->model.home;
            for (int k = 0; k < 3; ++k) a.mutable_data()[k] = p.position[k];
            for (int k = 0; k < 3; ++k) a.mutable_data()[3 + k] = radToDeg(p.rpy[k]);
            return a;
          },
          "(6,) home pose x, y, z, a, b, c (degrees): the FK seed.")
      .def("with_geometry",
           &withGeometry,
           py::arg("base_joints") = py::none(),
           py::arg("platform_joints") = py::none(),
           py::arg("length_offsets") = py::none(),
           py::arg("stroke") = py::none(),
           py::arg("tool_offset") = py::none(),
           "A new Hexapod with some geometry replaced (arrays shaped as the properties of the "
           "same name; joint cones, limits and home are kept).\n\n"
           "Raises\n------\nValueError\n    when the new geometry is unusable (pkm's message).");
}

}  // namespace pkm::python
