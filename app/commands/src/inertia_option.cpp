// The --inertia option inspect and inertials share.
#include "inertia_option.hpp"

#include <string>

namespace tumble::app {

void add_inertia_option(CLI::App& command, engine::InertiaMethod& method) {
  command
      .add_option_function<std::string>(
          "--inertia",
          [&method](const std::string& name) {
            method = engine::parse_inertia_method(name).value_or(engine::InertiaMethod::exact);
          },
          "How a mesh becomes inertia: exact (the solid a closed surface encloses; the "
          "default), convex (the convex hull's solid, for open or broken meshes), shell (the "
          "surface at uniform areal density: with --shell T or --mass M), legacy (MuJoCo's "
          "approximation, its default for meshes) or auto (exact, else convex with a warning "
          "naming why)")
      ->check(CLI::IsMember({"exact", "convex", "shell", "legacy", "auto"}))
      ->option_text("exact|convex|shell|legacy|auto");
}

}  // namespace tumble::app
