// A bench shard's job, its exact rows and its part folder.
#include "app/analysis/bench_part.hpp"

#include <set>

#include "app/analysis/row_parts.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"

namespace tumble::app {

namespace {
using nlohmann::json;  // file-local (a namespace-wide name would shadow `json` members)
}  // namespace

json bench_job(const BenchOptions& options) {
  return {{"command", "bench"},
          {"scenes", scene_inputs_json(options.scenes)},
          {"options",
           {{"integrators", optional_text(options.integrators)},
            {"dts", optional_text(options.dts)},
            {"tolerances", optional_text(options.tolerances)},
            {"duration", optional_text(options.duration)},
            {"repeat", optional_text(options.repeat)}}}};
}

BenchOptions bench_job_options(const json& job) {
  BenchOptions options;
  options.scenes = unchanged_scene_inputs(job.at("scenes"));
  const json& given = job.at("options");
  options.integrators = text_option(given.at("integrators"));
  options.dts = text_option(given.at("dts"));
  options.tolerances = text_option(given.at("tolerances"));
  options.duration = text_option(given.at("duration"));
  options.repeat = text_option(given.at("repeat"));
  return options;
}

json case_result_json(const CaseResult& r) {
  json seconds = json::array();
  for (const double s : r.seconds) seconds.push_back(exact_number(s));
  const ErrorFigures& e = r.errors;
  return {{"steps", r.steps},
          {"total_steps", r.total_steps},
          {"blow_up_time", r.blow_up_time ? exact_number(*r.blow_up_time) : json(nullptr)},
          {"blow_up_reason", r.blow_up_reason},
          {"counts",
           {{"accepted", r.counts.accepted},
            {"rejected", r.counts.rejected},
            {"evaluations", r.counts.evaluations}}},
          {"seconds", seconds},
          {"median_seconds", exact_number(r.median_seconds)},
          {"min_seconds", exact_number(r.min_seconds)},
          {"max_seconds", exact_number(r.max_seconds)},
          {"errors",
           {{"orientation_final", exact_number(e.orientation_final)},
            {"orientation_max", exact_number(e.orientation_max)},
            {"omega_final", exact_number(e.omega_final)},
            {"omega_max", exact_number(e.omega_max)},
            {"momentum_final", exact_number(e.momentum_final)},
            {"momentum_max", exact_number(e.momentum_max)},
            {"energy_drift_max", exact_number(e.energy_drift_max)},
            {"momentum_norm_drift_max", exact_number(e.momentum_norm_drift_max)},
            {"samples", e.samples}}},
          {"core", r.core}};
}

CaseResult case_result_from_json(const json& j, const std::string& source) {
  try {
    CaseResult r;
    const auto number = [&](const json& value, const char* field) {
      return exact_number_value(value, source, std::string("payload.results.") + field);
    };
    r.steps = j.at("steps").get<std::size_t>();
    r.total_steps = j.at("total_steps").get<std::size_t>();
    if (!j.at("blow_up_time").is_null()) r.blow_up_time = number(j.at("blow_up_time"), "time");
    r.blow_up_reason = j.at("blow_up_reason").get<std::string>();
    r.counts.accepted = j.at("counts").at("accepted").get<std::size_t>();
    r.counts.rejected = j.at("counts").at("rejected").get<std::size_t>();
    r.counts.evaluations = j.at("counts").at("evaluations").get<std::size_t>();
    for (const json& s : j.at("seconds")) r.seconds.push_back(number(s, "seconds"));
    r.median_seconds = number(j.at("median_seconds"), "median_seconds");
    r.min_seconds = number(j.at("min_seconds"), "min_seconds");
    r.max_seconds = number(j.at("max_seconds"), "max_seconds");
    const json& e = j.at("errors");
    for (const auto& [field, member] :
         {std::pair{"orientation_final", &ErrorFigures::orientation_final},
          {"orientation_max", &ErrorFigures::orientation_max},
          {"omega_final", &ErrorFigures::omega_final},
          {"omega_max", &ErrorFigures::omega_max},
          {"momentum_final", &ErrorFigures::momentum_final},
          {"momentum_max", &ErrorFigures::momentum_max},
          {"energy_drift_max", &ErrorFigures::energy_drift_max},
          {"momentum_norm_drift_max", &ErrorFigures::momentum_norm_drift_max}}) {
      r.errors.*member = number(e.at(field), field);
    }
    r.errors.samples = e.at("samples").get<std::size_t>();
    r.core = j.at("core").get<int>();
    return r;
  } catch (const json::exception& error) {
    throw InputError(source + ": field 'payload.results': " + error.what());
  }
}

namespace {

json reference_json(const Reference& reference) {
  json check = nullptr;
  if (reference.check) {
    check = {{"runs", reference.check->runs},
             {"orientation", exact_number(reference.check->orientation)},
             {"omega", exact_number(reference.check->omega)},
             {"momentum", exact_number(reference.check->momentum)}};
  }
  return {{"description", reference.description}, {"check", check}};
}

}  // namespace

void write_bench_part(const BenchOutcome& part, const std::vector<std::size_t>& items,
                      const nlohmann::json& job, Shard shard, std::size_t total,
                      const std::filesystem::path& tmp, const std::filesystem::path& output) {
  json results = json::array();
  std::set<std::size_t> scenes;
  for (std::size_t i = 0; i < part.cases.size(); ++i) {
    results.push_back(case_result_json(part.results[i]));
    scenes.insert(part.cases[i].scene);
  }
  json references = json::array();
  for (const std::size_t s : scenes) {
    references.push_back({{"scene", s}, {"reference", reference_json(part.scenes[s].reference)}});
  }
  const json payload = {{"data", "results.csv"},
                        {"cases", items},
                        {"results", results},
                        {"scenes", references},
                        {"workers",
                         {{"workers", part.workers},
                          {"cores_used", part.cores_used},
                          {"cores_available", part.cores_available}}}};
  try {
    write_results_csv(part, tmp / "results.csv");
    write_folder_manifest(tmp, row_part_manifest("bench", job, shard, total, payload));
  } catch (const WriteError& error) {
    throw output_write_error(error, tmp, output);
  }
}

OutputFolderKind bench_part_kind() {
  return part_folder_kind("bench", "results.csv");
}

}  // namespace tumble::app
