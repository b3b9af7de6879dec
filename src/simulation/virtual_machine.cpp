#include "pkm/simulation/virtual_machine.hpp"

#include "pkm/core/error.hpp"

namespace pkm::simulation {

void checkCommand(const Eigen::VectorXd& command, Eigen::Index axes) {
  PKM_CHECK(command.size() == axes, "command has {} axes, the machine {}", command.size(), axes);
  PKM_CHECK(command.allFinite(), "command is not finite");
}

}  // namespace pkm::simulation
