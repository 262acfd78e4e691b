// `tumble merge` of row parts: the dispatch between bench and stability.
#include "merge_rows.hpp"

namespace tumble::app {

void merge_row_parts(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                     std::ostream& out) {
  if (parts.front().manifest.kind == "bench") {
    merge_bench_parts(parts, output, out);
  } else {
    merge_stability_parts(parts, output, out);
  }
}

}  // namespace tumble::app
