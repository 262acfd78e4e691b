// The commands every job script runs: one shard, and the merge; bash quoting.
#include "app/farm/farm_scripts.hpp"

#include <cctype>

namespace tumble::app {

namespace {

bool safe_in_shell(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (std::isalnum(u) != 0) return true;
  return std::string_view("_@%+=:,./-").find(c) != std::string_view::npos;
}

/// The output as the merge is given it: a PNG folder with its '/', as render expects.
std::string merge_output_text(const FarmJob& job) {
  std::string text = job.output.string();
  if (job.form == PartForm::kPngFolder && job.output.extension() != ".gif" &&
      job.output.extension() != ".GIF") {
    text += '/';
  }
  return text;
}

/// `prefix` INDEX `suffix` as one bash word: the quoted texts around an expression bash
/// expands ("$SLURM_ARRAY_TASK_ID" or {0..3}); `index` as it is.
std::string spliced_word(std::string_view prefix, std::string_view index, std::string_view suffix) {
  std::string word = prefix.empty() ? "" : shell_quote(prefix);
  word += index;
  if (!suffix.empty()) word += shell_quote(suffix);
  return word;
}

/// OUT.parts/part-INDEX.EXT as one bash word, `index` spliced in (a '$' expression or braces)
/// or, when `expand` is false, kept in the quoted text (GNU parallel's {}).
std::string part_word(const FarmJob& job, std::string_view index, bool expand) {
  const std::string folder = parts_folder(job).string() + "/";
  if (!expand) return shell_quote(folder + part_file_name(job, index));
  const std::string marker = "\x01";
  const std::string name = part_file_name(job, marker);
  const std::size_t at = name.find(marker);
  return spliced_word(folder + name.substr(0, at), index, name.substr(at + marker.size()));
}

std::string command_words(const FarmJob& job, const std::filesystem::path& tumble) {
  std::string words = shell_quote(tumble.string()) + " " + job.command;
  for (const std::string& arg : job.args) words += " " + shell_quote(arg);
  return words;
}

}  // namespace

std::string shell_quote(std::string_view word) {
  bool safe = !word.empty();
  for (const char c : word) safe = safe && safe_in_shell(c);
  if (safe) return std::string(word);
  std::string quoted = "'";
  for (const char c : word) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

std::string shard_command(const FarmJob& job, const std::filesystem::path& tumble,
                          std::string_view index, int shards) {
  const bool expand = !index.empty() && index.front() == '"';
  const std::string count = "/" + std::to_string(shards);
  const std::string shard =
      expand ? spliced_word("", index, count) : shell_quote(std::string(index) + count);
  return command_words(job, tumble) + " --shard " + shard + " -o " + part_word(job, index, expand);
}

std::string merge_command(const FarmJob& job, const std::filesystem::path& tumble, int shards) {
  const std::string indices =
      shards == 1 ? std::string("0") : "{0.." + std::to_string(shards - 1) + "}";
  return shell_quote(tumble.string()) + " merge " + part_word(job, indices, true) + " -o " +
         shell_quote(merge_output_text(job));
}

}  // namespace tumble::app
