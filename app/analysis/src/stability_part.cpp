// A stability shard's job, its exact runs and its part folder.
#include "app/analysis/stability_part.hpp"

#include <utility>

#include "app/analysis/row_parts.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"

namespace tumble::app {

namespace {
using nlohmann::json;  // file-local (a namespace-wide name would shadow `json` members)
}  // namespace

json stability_job(const StabilityOptions& options) {
  return {{"command", "stability"},
          {"scenes", scene_inputs_json(options.scenes)},
          {"options",
           {{"suite", optional_text(options.suite)},
            {"cases", optional_text(options.cases)},
            {"integrators", optional_text(options.integrators)},
            {"dts", optional_text(options.dts)}}}};
}

StabilityOptions stability_job_options(const json& job) {
  StabilityOptions options;
  options.scenes = unchanged_scene_inputs(job.at("scenes"));
  const json& given = job.at("options");
  options.suite = text_option(given.at("suite"));
  options.cases = text_option(given.at("cases"));
  options.integrators = text_option(given.at("integrators"));
  options.dts = text_option(given.at("dts"));
  return options;
}

namespace {

/// The doubles of InvariantChanges, by name.
const std::pair<const char*, double InvariantChanges::*> kChanges[] = {
    {"energy_final", &InvariantChanges::energy_final},
    {"energy_max_gain", &InvariantChanges::energy_max_gain},
    {"energy_max_loss", &InvariantChanges::energy_max_loss},
    {"energy_late_min", &InvariantChanges::energy_late_min},
    {"energy_late_max", &InvariantChanges::energy_late_max},
    {"momentum_final", &InvariantChanges::momentum_final},
    {"momentum_max_gain", &InvariantChanges::momentum_max_gain},
    {"momentum_max_loss", &InvariantChanges::momentum_max_loss},
    {"momentum_late_min", &InvariantChanges::momentum_late_min},
    {"momentum_late_max", &InvariantChanges::momentum_late_max}};

/// The optional doubles of StabilityRun, by name.
const std::pair<const char*, std::optional<double> StabilityRun::*> kOptionals[] = {
    {"blowup_time", &StabilityRun::blowup_time},
    {"orientation_error", &StabilityRun::orientation_error},
    {"position_error", &StabilityRun::position_error},
    {"momentum_error", &StabilityRun::momentum_error}};

/// The doubles of StabilityRun, by name.
const std::pair<const char*, double StabilityRun::*> kNumbers[] = {
    {"dt", &StabilityRun::dt},
    {"rate_dt", &StabilityRun::rate_dt},
    {"duration", &StabilityRun::duration},
    {"motion_range", &StabilityRun::motion_range},
    {"wall_seconds", &StabilityRun::wall_seconds}};

}  // namespace

json stability_run_json(const StabilityRun& r) {
  json changes = {{"energy_applies", r.changes.energy_applies},
                  {"momentum_applies", r.changes.momentum_applies}};
  for (const auto& [name, member] : kChanges) changes[name] = exact_number(r.changes.*member);
  json out = {{"case", r.case_name},
              {"integrator", r.integrator},
              {"steps", r.steps},
              {"total_steps", r.total_steps},
              {"outcome", static_cast<int>(r.outcome)},
              {"changes", changes},
              {"blowup_reason", r.blowup_reason},
              {"reference_instants", r.reference_instants},
              {"reference", r.reference},
              {"note", r.note}};
  for (const auto& [name, member] : kNumbers) out[name] = exact_number(r.*member);
  for (const auto& [name, member] : kOptionals) {
    out[name] = (r.*member) ? exact_number(*(r.*member)) : json(nullptr);
  }
  return out;
}

StabilityRun stability_run_from_json(const json& j, const std::string& source) {
  try {
    StabilityRun r;
    const auto number = [&](const json& value, const char* field) {
      return exact_number_value(value, source, std::string("payload.runs.") + field);
    };
    r.case_name = j.at("case").get<std::string>();
    r.integrator = j.at("integrator").get<std::string>();
    r.steps = j.at("steps").get<std::size_t>();
    r.total_steps = j.at("total_steps").get<std::size_t>();
    const int outcome = j.at("outcome").get<int>();
    if (outcome < 0 || outcome >= kStabilityOutcomeCount) {
      throw InputError(source + ": field 'payload.runs.outcome': out of range");
    }
    r.outcome = static_cast<StabilityOutcome>(outcome);
    const json& changes = j.at("changes");
    r.changes.energy_applies = changes.at("energy_applies").get<bool>();
    r.changes.momentum_applies = changes.at("momentum_applies").get<bool>();
    for (const auto& [name, member] : kChanges) r.changes.*member = number(changes.at(name), name);
    r.blowup_reason = j.at("blowup_reason").get<std::string>();
    r.reference_instants = j.at("reference_instants").get<std::size_t>();
    r.reference = j.at("reference").get<std::string>();
    r.note = j.at("note").get<std::string>();
    for (const auto& [name, member] : kNumbers) r.*member = number(j.at(name), name);
    for (const auto& [name, member] : kOptionals) {
      if (!j.at(name).is_null()) r.*member = number(j.at(name), name);
    }
    return r;
  } catch (const json::exception& error) {
    throw InputError(source + ": field 'payload.runs': " + error.what());
  }
}

void write_stability_part(const std::string& suite, const std::vector<StabilityCase>& cases,
                          const std::vector<StabilityRun>& runs,
                          const std::vector<std::size_t>& items, const json& job, Shard shard,
                          std::size_t total, const std::filesystem::path& tmp,
                          const std::filesystem::path& output) {
  json exact = json::array();
  for (const StabilityRun& run : runs) exact.push_back(stability_run_json(run));
  const json payload = {{"data", "stability.csv"}, {"runs", items}, {"results", exact}};
  try {
    write_text_file(tmp / "stability.csv", stability_csv(suite, cases, runs));
    write_folder_manifest(tmp, row_part_manifest("stability", job, shard, total, payload));
  } catch (const WriteError& error) {
    throw output_write_error(error, tmp, output);
  }
}

OutputFolderKind stability_part_kind() {
  return part_folder_kind("stability", "stability.csv");
}

}  // namespace tumble::app
