// The extension module pkm._pkm (docs/python.md): each area registers its bindings.
#include "common.hpp"
#include "simulation.hpp"

PYBIND11_MODULE(_pkm, m) {
  m.doc() =
      "pkm: kinematics, metrology and calibration of parallel kinematic machine tools "
      "(hexapods, Exechon tripods). Lengths are in the machine's unit (mm or inch), angles in "
      "degrees at this boundary, as in the pkm command line.";
  namespace p = pkm::python;
  p::exposeErrors(m);
  p::exposeMachines(m);
  p::exposeHexapod(m);
  p::exposeExechon(m);
  p::exposeMetrology(m);
  p::exposeCalibration(m);
  p::exposeSimulation(m);
  p::exposeCampaign(m);
  p::exposeGcode(m);
}
