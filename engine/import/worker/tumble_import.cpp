// tumble-import: the import worker, started by tumble (and by the Python module) to read mesh
// files with assimp in a process of its own (engine/import/src/import_worker.hpp says why).
// It is not meant to be run by hand.
#include <array>
#include <iostream>

#include "assimp_reader.hpp"
#include "worker_serve.hpp"

int main(int argc, char** argv) {
  using namespace tumble::engine::detail;
  if (!started_as_worker(argc, argv)) {
    std::cerr << "tumble-import: the import worker of tumble; tumble starts it, it is not run by "
                 "hand\n";
    return 2;
  }
  const std::array tasks{WorkerTaskEntry{kAssimpTask, read_with_assimp}};
  return serve_import_requests(argc, argv, tasks);
}
