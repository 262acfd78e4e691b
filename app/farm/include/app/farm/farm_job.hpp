#pragma once
/// @file A tumble command turned into a farmed job (`tumble farm slurm|parallel -- COMMAND`):
/// which command it is, its arguments with every path made absolute, its output `-o OUT`, and
/// the parts its N shards write (`OUT.parts/part-I.EXT`), so that the scripts of
/// farm_scripts.hpp can run shard I anywhere and `tumble merge` can put the parts together.
///
/// The command is read with each command's own option table (kFarmedCommands): which options
/// take a value, so that every other word is an input path. A test holds the table to the real
/// commands' options (tests/app/farm/farm_job_test.cpp).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::app {

/// One option of a farmed command: its names ("-o,--output") and whether it takes a value.
struct FarmedOption {
  std::string_view names;
  bool takes_value;
};

/// What a command's output is, and so what its parts are.
enum class PartForm {
  kVideo,       ///< render, compare: .mp4, .webm (parts of the same container)
  kPngFolder,   ///< render, compare: a PNG folder (parts are PNG folders); also for a .gif
  kRowsFolder,  ///< bench, stability: a folder of rows
  kJsonLines,   ///< inspect: .jsonl parts (the output .jsonl or .json)
};

/// A command `tumble farm` can shard, and its options besides -o and --shard.
struct FarmedCommand {
  std::string_view name;
  std::vector<FarmedOption> options;
};

/// render, compare, bench, stability, inspect.
const std::vector<FarmedCommand>& farmed_commands();

/// The tumble command of a farmed job.
struct FarmJob {
  std::string command;            ///< render, compare, bench, stability, inspect
  std::vector<std::string> args;  ///< after the command's name, without -o OUT; paths absolute
  std::filesystem::path output;   ///< OUT, absolute, without a trailing '/'
  PartForm form = PartForm::kVideo;
  std::vector<std::filesystem::path> inputs;  ///< the input paths named, absolute
  std::filesystem::path tumble;               ///< the executable named before the command, if any
};

/// Reads `words`, a tumble command: optionally "tumble" or a path to a tumble executable, then
/// the command's name and its arguments. Relative paths are taken from `cwd`. Throws InputError
/// (one line, "tumble render ...: WHAT") for an unknown command or option, a missing value, a
/// command with --shard already, no -o OUT, an output the command cannot shard, or a word GNU
/// parallel or the scripts could not carry (a newline).
FarmJob parse_farm_job(const std::vector<std::string>& words, const std::filesystem::path& cwd);

/// OUT.parts: the folder of the parts.
std::filesystem::path parts_folder(const FarmJob& job);
/// The name of part `index` for the form of `job`, as `-o` is given it: "part-3.mp4",
/// "part-3/" (a PNG folder, the slash telling render so), "part-3" (rows), "part-3.jsonl".
/// `index` may be a shell expression ("$SLURM_ARRAY_TASK_ID", "{}"), kept as it is.
std::string part_file_name(const FarmJob& job, std::string_view index);

}  // namespace tumble::app
