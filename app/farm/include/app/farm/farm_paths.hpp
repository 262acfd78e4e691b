#pragma once
/// @file Whether the workers of a farmed job can reach its files: every input must exist, the
/// output's folder must exist, the tumble executable must run; and with workers on other
/// machines (Slurm, GNU parallel over ssh) each of those paths must be on a filesystem they
/// share. Which filesystem a path is on comes from statfs(2)'s f_type.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/farm/farm_job.hpp"

namespace tumble::app {

/// What a filesystem is to the workers.
enum class Sharing {
  kNetwork,  ///< NFS, CIFS/SMB, Lustre, GPFS, BeeGFS, CephFS, ...: workers may mount it too
  kLocal,    ///< ext4, xfs, btrfs, tmpfs, overlay, ...: this machine's only
  kUnknown,  ///< FUSE (sshfs, GlusterFS, ...) or a type tumble does not know
};

struct FilesystemKind {
  std::string name;  ///< "nfs", "tmpfs", "fuse", "0x1234abcd"
  Sharing sharing = Sharing::kUnknown;
};

/// The filesystem of statfs's `f_type`.
FilesystemKind filesystem_kind(std::int64_t f_type);
/// The filesystem `path` is on (its nearest existing ancestor's); throws InputError when statfs
/// fails.
FilesystemKind filesystem_of(const std::filesystem::path& path);

/// The paths a farmed job's workers read or write: the inputs, extra inputs (a scene's meshes),
/// the output's folder, the tumble executable (and tumble-draw beside it for render and
/// compare).
struct JobPaths {
  std::vector<std::filesystem::path> inputs;
  std::filesystem::path output_folder;
  std::vector<std::filesystem::path> executables;
};

/// The paths of `job` (its inputs plus `extra_inputs`) run by `tumble`.
JobPaths job_paths(const FarmJob& job, const std::filesystem::path& tumble,
                   const std::vector<std::filesystem::path>& extra_inputs);

/// Checks that every input exists, the output folder is a folder and the executables are
/// executable files; throws InputError naming the first that is not ("input '/x/a.json': no
/// such file").
void check_job_paths(const JobPaths& paths);

/// For workers on other machines: one line per path on a local filesystem ("'/tmp/x' is on a
/// local filesystem (tmpfs); workers on other machines will not see it") or one of unknown
/// sharing ("... (fuse): tumble cannot tell whether workers on other machines see it").
/// Executables on a local filesystem are named as "must be installed at the same path on
/// every worker" rather than as unseen. `local` is set when an input or the output folder is
/// on a local filesystem (the error case of tumble farm unless --assume-shared).
std::vector<std::string> sharing_notes(const JobPaths& paths, bool& local);

}  // namespace tumble::app
