// Submitting the scripts of farm_slurm.cpp with sbatch, and following the jobs with scontrol.
#include "app/farm/farm_slurm_run.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "app/support/file_write.hpp"
#include "base/errors.hpp"
#include "base/process.hpp"

namespace tumble::app {

namespace {

/// The values of `key` in each line (record) of `text`.
std::vector<std::string> record_values(const std::string& text, const std::string& key) {
  std::vector<std::string> values;
  const std::regex field("(?:^| )" + key + "=(\\S*)");
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find("JobId=") == std::string::npos) continue;
    std::smatch match;
    values.push_back(std::regex_search(line, match, field) ? match[1].str() : std::string());
  }
  return values;
}

/// The last line of a job's log, for a message ("" when there is none).
std::string log_tail(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string line = last_line(text.str());
  return line.empty() ? "" : ": " + line;
}

/// Runs a Slurm tool (a missing one throws tumble::InputError "sbatch not found on PATH"); one
/// that exits 127 (a wrapper that cannot run it) is named with its last line.
ProcessResult slurm_tool(const std::vector<std::string>& argv) {
  ProcessResult result = run_process(argv);
  if (result.shell_status() == 127) throw InputError(argv[0] + ": " + last_line(result.err));
  return result;
}

std::string submit(const std::vector<std::string>& argv) {
  const ProcessResult result = slurm_tool(argv);
  if (result.status != 0) {
    throw InputError("sbatch failed (exit status " + std::to_string(result.shell_status()) +
                     "): " + last_line(result.err));
  }
  return parsable_job_id(result.out);
}

/// Throws when a task of the array job ended other than COMPLETED, after every task ended.
void check_shards(const FarmJob& job, const SlurmJobIds& ids) {
  const ProcessResult shown = slurm_tool({"scontrol", "show", "job", "-o", ids.shards});
  if (shown.status != 0) return;  // gone from the controller: the merge job's state says more
  const std::vector<std::string> states = job_states(shown.out);
  const std::vector<std::string> tasks = array_task_ids(shown.out);
  std::vector<std::pair<long, std::string>> ended;  // task, state; scontrol lists them backwards
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (!final_job_state(states[i])) return;
    if (states[i] != "COMPLETED") ended.emplace_back(std::atol(tasks[i].c_str()), states[i]);
  }
  std::sort(ended.begin(), ended.end());
  std::string failed;
  for (const auto& [task, state] : ended) {
    failed += (failed.empty() ? "" : ", ") + std::to_string(task) + " " + state;
  }
  const std::string first = ended.empty() ? "" : std::to_string(ended.front().first);
  if (failed.empty()) return;
  slurm_tool({"scancel", ids.merge});
  const std::filesystem::path log =
      parts_folder(job) / ("slurm-" + ids.shards + "_" + first + ".out");
  throw InputError("Slurm job " + ids.shards + ": shard task " + failed + "; merge job " +
                   ids.merge + " cancelled; see '" + log.string() + "'" + log_tail(log));
}

}  // namespace

std::string parsable_job_id(const std::string& output) {
  std::string id = output.substr(0, output.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    throw InputError("sbatch --parsable printed '" + last_line(output) + "', not a job id");
  }
  return id;
}

std::vector<std::string> job_states(const std::string& scontrol_output) {
  return record_values(scontrol_output, "JobState");
}

std::vector<std::string> array_task_ids(const std::string& scontrol_output) {
  return record_values(scontrol_output, "ArrayTaskId");
}

bool final_job_state(const std::string& state) {
  static const char* const kLive[] = {"PENDING",   "RUNNING",      "CONFIGURING", "COMPLETING",
                                      "SUSPENDED", "REQUEUED",     "RESIZING",    "SIGNALING",
                                      "STAGE_OUT", "REQUEUE_HOLD", "REQUEUE_FED", "RESV_DEL_HOLD",
                                      "STOPPED"};
  for (const char* live : kLive) {
    if (state == live) return false;
  }
  return !state.empty();
}

SlurmJobIds submit_slurm_job(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                             const SlurmResources& resources) {
  const std::filesystem::path parts = parts_folder(job);
  std::error_code error;
  std::filesystem::create_directories(parts, error);
  if (error) {
    throw InputError("cannot create '" + parts.string() + "': " + error.message());
  }
  const std::filesystem::path shards_script = parts / "shards.sbatch";
  const std::filesystem::path merge_script = parts / "merge.sbatch";
  write_text_file(shards_script, slurm_array_script(job, tumble, shards, resources));
  write_text_file(merge_script, slurm_merge_script(job, tumble, shards, resources));
  SlurmJobIds ids;
  ids.shards =
      submit({"sbatch", "--parsable", slurm_log_option(job, false)[0], shards_script.string()});
  ids.merge = submit({"sbatch", "--parsable", "--dependency=afterok:" + ids.shards,
                      slurm_log_option(job, true)[0], merge_script.string()});
  return ids;
}

void wait_for_slurm_job(const FarmJob& job, const SlurmJobIds& ids,
                        std::chrono::milliseconds poll) {
  for (;;) {
    const ProcessResult shown = slurm_tool({"scontrol", "show", "job", "-o", ids.merge});
    if (shown.status != 0) {
      throw InputError("Slurm job " + ids.merge +
                       " (the merge): scontrol: " + last_line(shown.err));
    }
    const std::vector<std::string> states = job_states(shown.out);
    const std::string state = states.empty() ? "" : states.front();
    if (state == "COMPLETED") return;
    if (final_job_state(state)) {
      const std::filesystem::path log = parts_folder(job) / ("slurm-" + ids.merge + "-merge.out");
      throw InputError("Slurm job " + ids.merge + " (the merge) ended " + state + "; see '" +
                       log.string() + "'" + log_tail(log));
    }
    if (state == "PENDING") check_shards(job, ids);
    std::this_thread::sleep_for(poll);
  }
}

}  // namespace tumble::app
