#include "app/analysis/blow_up.hpp"

#include "app/support/printf_number.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {

std::string describe_blow_up(const engine::Simulation& simulation) {
  const auto& blow_up = simulation.blow_up();
  if (!blow_up) return {};
  return "body '" + simulation.bodies()[blow_up->body].name + "' at step " +
         std::to_string(blow_up->step) + " (t = " + printf_number(blow_up->time, "%.9g") +
         " s): " + blow_up->reason;
}

}  // namespace tumble::app
