// The GNU parallel command line of a farmed job: the shards over hosts or local slots, then the
// merge.
#include "app/farm/farm_scripts.hpp"
#include "base/errors.hpp"

namespace tumble::app {

std::string parallel_command_line(const FarmJob& job, const std::filesystem::path& tumble,
                                  int shards, const ParallelSlots& slots) {
  for (const std::string& arg : job.args) {
    if (arg.find('{') != std::string::npos && arg.find('}') != std::string::npos) {
      throw InputError("'" + arg +
                       "': GNU parallel would take its braces for a replacement string; rename "
                       "it or use tumble farm slurm");
    }
  }
  std::string hosts;
  for (const std::string& host : slots.hosts) {
    if (host.empty() || host.find_first_of(", \t'\"") != std::string::npos) {
      throw InputError("-S: expected host names separated by commas, got '" + host + "'");
    }
    hosts += (hosts.empty() ? "" : ",") + host;
  }
  if (slots.jobs && *slots.jobs < 1) {
    throw InputError("--jobs: expected at least 1 shard at once per host, got " +
                     std::to_string(*slots.jobs));
  }
  std::string line = "mkdir -p -- " + shell_quote(parts_folder(job).string()) +
                     " && parallel -q --halt now,fail=1";
  if (slots.jobs) line += " --jobs " + std::to_string(*slots.jobs);
  if (!hosts.empty()) line += " -S " + shell_quote(hosts);
  line += " " + shard_command(job, tumble, "{}", shards) + " ::: ";
  line += shards == 1 ? std::string("0") : "{0.." + std::to_string(shards - 1) + "}";
  return line + " && " + merge_command(job, tumble, shards);
}

}  // namespace tumble::app
