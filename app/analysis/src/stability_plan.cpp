// `tumble stability`'s plan (its integrators and cases, in the order the runs are made) and its
// output folder from the runs: what the command and `tumble merge` share.
#include "app/analysis/stability_plan.hpp"

#include <algorithm>

#include "app/analysis/gnuplot.hpp"
#include "app/analysis/stability_plot.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/scene/option_lists.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"

namespace tumble::app {

using tumble::InputError;
namespace fs = std::filesystem;

/// The integrators --integrators names (each name checked), or every one.
std::vector<engine::IntegratorInfo> parse_stability_integrators(
    const std::optional<std::string>& text) {
  if (!text) return engine::integrator_catalog();
  std::vector<engine::IntegratorInfo> chosen;
  for (const engine::IntegratorInfo* info : parse_integrator_list(*text, "--integrators")) {
    chosen.push_back(*info);
  }
  return chosen;
}

/// The cases to run: the suite's (filtered by --cases), then the scene files.
std::vector<StabilityCase> gather_stability_cases(const StabilityOptions& options,
                                                  std::string& suite_name) {
  std::optional<std::vector<double>> dts;
  if (options.dts) dts = parse_positive_list(*options.dts, "--dts");
  std::vector<StabilityCase> cases;
  const bool use_suite = options.suite || options.cases || options.scenes.empty();
  if (use_suite) {
    StabilitySuite suite = stability_suite(options.suite.value_or("standard"));
    suite_name = suite.name;
    if (options.cases) {
      for (const std::string& name : split_option_list(*options.cases, "--cases")) {
        const auto found = std::find_if(suite.cases.begin(), suite.cases.end(),
                                        [&](const StabilityCase& c) { return c.name == name; });
        if (found == suite.cases.end()) {
          std::string names;
          for (const StabilityCase& c : suite.cases) names += (names.empty() ? "" : ", ") + c.name;
          throw InputError("--cases: no case '" + name + "' in suite '" + suite.name +
                           "'; expected one of: " + names);
        }
        cases.push_back(*found);
      }
    } else {
      cases = std::move(suite.cases);
    }
  }
  for (const fs::path& scene : options.scenes) cases.push_back(scene_case(scene, dts));
  return cases;
}

/// Writes the CSV, the markdown report and the heat map into the temporary folder `temporary`;
/// a failed write is named by its final name in `output` (nothing is written there).
void write_stability_folder(const std::string& suite, const std::vector<StabilityCase>& cases,
                            const std::vector<engine::IntegratorInfo>& integrators,
                            const std::vector<StabilityRun>& runs, const fs::path& temporary,
                            const fs::path& output) {
  try {
    write_text_file(temporary / "stability.csv", stability_csv(suite, cases, runs));
    write_text_file(temporary / "stability.md",
                    stability_markdown(suite, cases, integrators, runs));
    draw_heat_map(stability_heat_map(cases, integrators, runs), temporary / "stability.png",
                  temporary / "stability.svg");
  } catch (const WriteError& error) {
    throw output_write_error(error, temporary, output);
  }
}

const OutputFolderKind kStabilityOutput{"stability", "stability.md", "# tumble stability",
                                        "stability.csv"};

std::size_t stability_run_count(const std::vector<StabilityCase>& cases, std::size_t integrators) {
  std::size_t runs = 0;
  for (const StabilityCase& c : cases) runs += integrators * c.dts.size();
  return runs;
}

}  // namespace tumble::app
