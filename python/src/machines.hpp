/// @file
/// @brief The Python machine objects: a Hexapod or an Exechon holds the io machine it was loaded
/// as (model, solver settings, provenance), shared and never modified (a changed geometry is a new
/// object).
#pragma once

#include <memory>

#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace pkm::python {

/// pkm.Hexapod.
struct Hexapod {
  std::shared_ptr<const io::HexapodMachine> machine;
};

/// pkm.Exechon.
struct Exechon {
  std::shared_ptr<const io::ExechonMachine> machine;
};

}  // namespace pkm::python
