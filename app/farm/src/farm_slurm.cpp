// The Slurm scripts of a farmed job: the array job of the shards, the merge job depending on it,
// and the bash script that submits both.
#include <regex>

#include "app/farm/farm_scripts.hpp"
#include "base/errors.hpp"

namespace tumble::app {

namespace {

/// Whether `text` is non-empty and every character is alphanumeric or one of `extra`.
bool plain_word(const std::string& text, std::string_view extra) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 &&
        extra.find(c) == std::string_view::npos) {
      return false;
    }
  }
  return true;
}

void check_word(const std::string& value, const char* option, std::string_view extra,
                const char* what) {
  if (!value.empty() && !plain_word(value, extra)) {
    throw InputError(std::string(option) + ": expected " + what + ", got '" + value + "'");
  }
}

/// The '%' of a path doubled, so that Slurm's --output patterns (%A, %a, %j) leave it alone.
std::string slurm_literal(const std::string& path) {
  std::string text;
  for (const char c : path) {
    text += c;
    if (c == '%') text += '%';
  }
  return text;
}

std::string sbatch_line(const std::string& option, const std::string& value) {
  return value.empty() ? "" : "#SBATCH --" + option + "=" + value + "\n";
}

/// The header both scripts start with, and the resources both take.
std::string script_head(const std::string& what, const std::string& name,
                        const SlurmResources& resources) {
  return "#!/bin/bash\n# " + what + "\n" + sbatch_line("job-name", name) +
         sbatch_line("partition", resources.partition) + sbatch_line("account", resources.account) +
         sbatch_line("time", resources.time);
}

std::string original_command(const FarmJob& job) {
  std::string text = "tumble " + job.command;
  for (const std::string& arg : job.args) text += " " + shell_quote(arg);
  return text + " -o " + shell_quote(job.output.string());
}

}  // namespace

void check_slurm_resources(const SlurmResources& resources) {
  check_word(resources.job_name, "--job-name", "._+-", "a name of letters, digits and ._+-");
  check_word(resources.partition, "--partition", "._-,", "partition names (letters, digits, ._-)");
  check_word(resources.account, "--account", "._-", "an account name (letters, digits, ._-)");
  static const std::regex time(
      R"((\d+|\d+:\d\d?|\d+:\d\d?:\d\d?|\d+-\d+|\d+-\d+:\d\d?|\d+-\d+:\d\d?:\d\d?|UNLIMITED))");
  if (!resources.time.empty() && !std::regex_match(resources.time, time)) {
    throw InputError(
        "--time: expected minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS, got '" +
        resources.time + "'");
  }
  static const std::regex mem(R"(\d+[KMGT]?)");
  if (!resources.mem.empty() && !std::regex_match(resources.mem, mem)) {
    throw InputError("--mem: expected megabytes N or N with K, M, G or T (e.g. 4G), got '" +
                     resources.mem + "'");
  }
  if (resources.cpus_per_task && *resources.cpus_per_task < 1) {
    throw InputError("--cpus-per-task: expected at least 1, got " +
                     std::to_string(*resources.cpus_per_task));
  }
  if (resources.max_running && *resources.max_running < 1) {
    throw InputError("--max-running: expected at least 1 task at once, got " +
                     std::to_string(*resources.max_running));
  }
}

std::string slurm_job_name(const FarmJob& job, const SlurmResources& resources) {
  if (!resources.job_name.empty()) return resources.job_name;
  std::string name = "tumble-" + job.command + "-" + job.output.filename().string();
  for (char& c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '.' && c != '_' && c != '-') {
      c = '_';
    }
  }
  return name;
}

std::string slurm_array_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                               const SlurmResources& resources) {
  std::string array = "0-" + std::to_string(shards - 1);
  if (resources.max_running) array += "%" + std::to_string(*resources.max_running);
  std::string script = script_head("tumble farm: shard $SLURM_ARRAY_TASK_ID of " +
                                       std::to_string(shards) + " of " + original_command(job),
                                   slurm_job_name(job, resources), resources);
  script += sbatch_line("array", array);
  if (resources.cpus_per_task) {
    script += sbatch_line("cpus-per-task", std::to_string(*resources.cpus_per_task));
  }
  script += sbatch_line("mem", resources.mem);
  return script + "exec " + shard_command(job, tumble, "\"$SLURM_ARRAY_TASK_ID\"", shards) + "\n";
}

std::string slurm_merge_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                               const SlurmResources& resources) {
  return script_head("tumble farm: the merge of the " + std::to_string(shards) + " parts of " +
                         original_command(job),
                     slurm_job_name(job, resources) + "-merge", resources) +
         "exec " + merge_command(job, tumble, shards) + "\n";
}

std::vector<std::string> slurm_log_option(const FarmJob& job, bool merge) {
  const std::string folder = slurm_literal(parts_folder(job).string());
  return {"--output=" + folder + (merge ? "/slurm-%j-merge.out" : "/slurm-%A_%a.out")};
}

std::string slurm_submit_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                                const SlurmResources& resources) {
  const std::string parts = parts_folder(job).string();
  std::string script =
      "#!/bin/bash\n"
      "# tumble farm slurm: " +
      original_command(job) + "\n# in " + std::to_string(shards) +
      " shards (a Slurm array job), then tumble merge (a job that starts when every shard has\n"
      "# succeeded). Submit with bash (this script) or tumble farm slurm --submit. Parts and\n"
      "# Slurm's logs go to " +
      parts +
      "/.\n"
      "set -euo pipefail\n"
      "mkdir -p -- " +
      shell_quote(parts) + "\n";
  script += "shards=$(sbatch --parsable " + shell_quote(slurm_log_option(job, false)[0]) +
            " <<'TUMBLE_SHARDS'\n" + slurm_array_script(job, tumble, shards, resources) +
            "TUMBLE_SHARDS\n)\nshards=${shards%%;*}\n";
  script += "merge=$(sbatch --parsable --dependency=afterok:\"$shards\" " +
            shell_quote(slurm_log_option(job, true)[0]) + " <<'TUMBLE_MERGE'\n" +
            slurm_merge_script(job, tumble, shards, resources) + "TUMBLE_MERGE\n)\n";
  return script + "echo \"shards: Slurm job $shards; merge: Slurm job ${merge%%;*}\"\n";
}

}  // namespace tumble::app
