#pragma once
// The import worker's task "assimp" (assimp_reader.cpp).

#include <string>
#include <vector>

#include "worker_serve.hpp"

namespace tumble::engine::detail {

/// The worker's name for read_with_assimp's task.
inline constexpr const char* kAssimpTask = "assimp";

/// Reads request[0] (a path) with assimp and writes the scene (raw_scene.hpp) into `out`.
/// Errors name request[1], the file as the user gave it.
void read_with_assimp(const std::vector<std::string>& request, AnswerWriter& out);

}  // namespace tumble::engine::detail
