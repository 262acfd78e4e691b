#pragma once
/// @file Trajectory CSV files, written atomically: under a temporary name in the same folder,
/// renamed into place only when complete, so no reader ever sees half a file under the final
/// name.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/body/rigid_body.hpp"

namespace tumble::app {

/// A file written under a temporary name and renamed to its final name by commit(). Until
/// then (and if commit() is never reached) the final name is untouched; the destructor removes
/// the temporary of an uncommitted file.
class AtomicFile {
 public:
  /// Creates the temporary `.NAME.tmp-PID` beside `path` (beside its target when `path` is a
  /// symbolic link to a regular file: the target is replaced, the link stays), first removing
  /// such temporaries of dead processes. Throws tumble::InputError naming `path` when it cannot
  /// be written (missing folder, no permission), when it is anything but a new name or a
  /// regular file (a directory, a device such as /dev/full, a FIFO: never replaced), or when it
  /// is the same file as one of `inputs` (the command's scene and meshes).
  explicit AtomicFile(std::filesystem::path path,
                      const std::vector<std::filesystem::path>& inputs = {});
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends bytes. Throws tumble::InputError naming the file on a write error (disk full).
  void write(std::string_view bytes);
  /// Flushes, closes and renames into place. Throws tumble::InputError on failure.
  void commit();

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }

 private:
  [[noreturn]] void fail(const std::string& what);

  std::filesystem::path path_;
  std::filesystem::path destination_;  ///< what is replaced: path_, or a link's target
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

/// The header of every trajectory CSV (world frame; L about the rotation centre).
inline constexpr std::string_view kTrajectoryHeader =
    "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz,energy";

/// Writes trajectory rows, one per body per written step, with 17 significant digits (every
/// double reads back exactly). Buffers in memory and writes in large blocks.
class TrajectoryCsv {
 public:
  /// Opens the temporary file and writes the header (see AtomicFile for errors).
  explicit TrajectoryCsv(std::filesystem::path path,
                         const std::vector<std::filesystem::path>& inputs = {});

  /// One row per body at time `t`: position, orientation of the user's body frame, velocity,
  /// world angular velocity, angular momentum and energy.
  void write_rows(double t, const std::vector<engine::BodyModel>& bodies,
                  const std::vector<engine::BodyState>& states);

  /// Writes what is buffered and renames the file into place.
  void commit();

  std::size_t rows() const { return rows_; }
  const std::filesystem::path& path() const { return file_.path(); }

 private:
  void flush();

  AtomicFile file_;
  std::string buffer_;
  std::size_t rows_ = 0;
};

/// `value` as printf("%.17g") writes it (reads back exactly), locale-independent.
void append_number(std::string& out, double value);

/// `text` as a CSV field (RFC 4180): quoted, with doubled quotes, only when it holds a comma,
/// a quote or a line break.
void append_csv_field(std::string& out, std::string_view text);

}  // namespace tumble::app
