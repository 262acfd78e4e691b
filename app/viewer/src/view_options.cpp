#include "app/viewer/view_options.hpp"

#include <system_error>

namespace tumble::app {

std::optional<std::filesystem::path> default_view_scene() {
  const std::filesystem::path demo =
      std::filesystem::path(TUMBLE_ASSETS_DIR) / "scenes" / "t_handle_flip.json";
  std::error_code error;
  if (std::filesystem::is_regular_file(demo, error)) return demo;
  return std::nullopt;
}

}  // namespace tumble::app
