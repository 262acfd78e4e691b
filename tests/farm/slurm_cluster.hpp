#pragma once
// A one-node Slurm cluster on the test machine, for the tests of `tumble farm slurm`: munged,
// slurmctld and slurmd (Debian's munge and slurm-wlm, from the install command; nothing is
// installed here) started as root with a minimal slurm.conf in a temporary folder, and stopped
// by their pids at the end. When it cannot be started (not root, a program missing, a daemon
// failing) `skip_reason()` says why, and the tests skip with it.

#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"

namespace tumble::testing {

class SlurmCluster {
 public:
  /// Starts the cluster; on failure leaves skip_reason() set and nothing running.
  SlurmCluster() {
    if (::geteuid() != 0) {
      reason_ = "a Slurm cluster is started only as root";
      return;
    }
    for (const char* program : {"munged", "slurmctld", "slurmd", "sbatch", "sinfo", "scontrol"}) {
      if (run_command(std::string("command -v ") + program).status != 0) {
        reason_ = std::string(program) + " is not installed (apt-get install slurm-wlm munge)";
        return;
      }
    }
    if (!std::filesystem::exists(kMungeKey)) {
      reason_ = std::string(kMungeKey) + " is missing (Debian's munge package makes it)";
      return;
    }
    char pattern[] = "/tmp/tumble_slurm_XXXXXX";
    if (::mkdtemp(pattern) == nullptr) {
      reason_ = "cannot make a temporary folder";
      return;
    }
    dir_ = pattern;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all |
                                           std::filesystem::perms::group_exec |
                                           std::filesystem::perms::others_exec);
    start();
  }
  ~SlurmCluster() {
    for (auto it = pids_.rbegin(); it != pids_.rend(); ++it) stop(*it);
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  /// Empty when the cluster runs.
  const std::string& skip_reason() const { return reason_; }
  const std::filesystem::path& folder() const { return dir_; }

 private:
  static constexpr const char* kMungeKey = "/etc/munge/munge.key";

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  void write_config() const {
    const std::string host = run_command("hostname -s").out;
    const std::string node = host.substr(0, host.find('\n'));
    // Ports of this test process only, so that another cluster (or run) does not answer.
    const int port = 20000 + 2 * static_cast<int>(::getpid() % 10000);
    std::ofstream conf(dir_ / "slurm.conf");
    conf << "ClusterName=tumbletest\nSlurmctldHost=" << node
         << "\nSlurmUser=root\nSlurmdUser=root\nAuthType=auth/munge\nAuthInfo=socket="
         << path("munge.socket") << "\nCredType=cred/munge\nProctrackType=proctrack/linuxproc\n"
         << "TaskPlugin=task/none\nSelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
         << "SlurmctldPort=" << port << "\nSlurmdPort=" << port + 1
         << "\nStateSaveLocation=" << path("state") << "\nSlurmdSpoolDir=" << path("spool")
         << "\nSlurmctldPidFile=" << path("slurmctld.pid")
         << "\nSlurmdPidFile=" << path("slurmd.pid")
         << "\nSlurmctldLogFile=" << path("slurmctld.log")
         << "\nSlurmdLogFile=" << path("slurmd.log")
         << "\nReturnToService=2\nMpiDefault=none\nJobAcctGatherType=jobacct_gather/none\n"
         << "AccountingStorageType=accounting_storage/none\nSchedulerType=sched/backfill\n"
         << "MinJobAge=600\nNodeName=" << node << " CPUs=2 RealMemory=20000 State=UNKNOWN\n"
         << "PartitionName=tumble Nodes=" << node << " Default=YES MaxTime=INFINITE State=UP\n";
  }

  /// Runs a daemon (it forks into the background) and keeps the pid it writes.
  bool daemon(const std::string& command, const std::string& pid_file, const std::string& log) {
    const CommandResult started = run_command(command);
    pid_t pid = 0;
    for (int i = 0; i < 50 && pid == 0; ++i) {
      std::ifstream(dir_ / pid_file) >> pid;
      if (pid == 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (started.status != 0 || pid <= 0) {
      reason_ = "'" + command + "' failed (status " + std::to_string(started.status) +
                "): " + started.err + read_text(dir_ / log);
      return false;
    }
    pids_.push_back(pid);
    return true;
  }

  void start() {
    for (const char* folder : {"state", "spool"}) std::filesystem::create_directory(dir_ / folder);
    write_config();
    ::setenv("SLURM_CONF", path("slurm.conf").c_str(), 1);
    const std::string conf = " -f " + path("slurm.conf");
    if (!daemon("munged --force --socket=" + path("munge.socket") + " --key-file=" + kMungeKey +
                    " --log-file=" + path("munged.log") + " --pid-file=" + path("munged.pid") +
                    " --seed-file=" + path("munged.seed"),
                "munged.pid", "munged.log") ||
        !daemon("slurmctld -i" + conf, "slurmctld.pid", "slurmctld.log") ||
        !daemon("slurmd" + conf, "slurmd.pid", "slurmd.log")) {
      return;
    }
    for (int i = 0; i < 300; ++i) {
      if (run_command("sinfo -h -N -o %T").out == "idle\n") return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    reason_ = "the Slurm node did not become idle in 30 s: " + run_command("sinfo -N").out +
              read_text(dir_ / "slurmd.log");
  }

  /// Whether `pid` runs (a zombie no longer does).
  static bool alive(pid_t pid) {
    if (::kill(pid, 0) != 0) return false;
    const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
    const std::size_t paren = stat.rfind(')');
    return paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] != 'Z';
  }

  static void stop(pid_t pid) {
    if (::kill(pid, SIGTERM) != 0) return;
    for (int i = 0; i < 100 && alive(pid); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ::kill(pid, SIGKILL);
  }

  std::filesystem::path dir_;
  std::vector<pid_t> pids_;
  std::string reason_;
};

}  // namespace tumble::testing
