// A tumble command read as a farmed job: options by each command's table, inputs made absolute,
// the output and the names of its parts.
#include "app/farm/farm_job.hpp"

#include <algorithm>
#include <cctype>

#include "base/errors.hpp"

namespace tumble::app {

namespace {

// The options render and compare share (app/commands/src/video_options_cli.cpp).
std::vector<FarmedOption> video_options(std::vector<FarmedOption> own) {
  std::vector<FarmedOption> options = {
      {"--size", true},       {"--fps", true}, {"--frames", true},   {"--time-scale", true},
      {"--font-scale", true}, {"--lod", true}, {"-q,--quiet", false}};
  options.insert(options.end(), own.begin(), own.end());
  return options;
}

/// Whether `names` ("-o,--output") holds `name` ("--output").
bool has_name(std::string_view names, std::string_view name) {
  while (!names.empty()) {
    const std::size_t comma = names.find(',');
    if (names.substr(0, comma) == name) return true;
    if (comma == std::string_view::npos) break;
    names.remove_prefix(comma + 1);
  }
  return false;
}

const FarmedCommand* find_command(std::string_view name) {
  for (const FarmedCommand& command : farmed_commands()) {
    if (command.name == name) return &command;
  }
  return nullptr;
}

const FarmedOption* find_option(const FarmedCommand& command, std::string_view name) {
  for (const FarmedOption& option : command.options) {
    if (has_name(option.names, name)) return &option;
  }
  return nullptr;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// The form of `output` for `command` (the rules of render's output, render/image_sink.cpp,
/// and of the parts of the design: rows folders, JSON Lines).
PartForm output_form(const std::string& command, const std::string& output, bool directory,
                     const std::string& where) {
  const std::string extension = lower(std::filesystem::path(output).extension().string());
  if (command == "bench" || command == "stability") return PartForm::kRowsFolder;
  if (command == "inspect") {
    if (extension == ".jsonl" || extension == ".json") return PartForm::kJsonLines;
    throw InputError(where + ": -o '" + output +
                     "': a farmed inspect writes .jsonl or .json (merged from JSON Lines parts)");
  }
  if ((!output.empty() && output.back() == '/') || directory) return PartForm::kPngFolder;
  if (extension == ".mp4" || extension == ".webm") return PartForm::kVideo;
  if (extension == ".gif") return PartForm::kPngFolder;
  throw InputError(where + ": -o '" + output +
                   "': expected a .mp4, .webm or .gif file or a folder ending in '/'");
}

std::string without_trailing_slashes(std::string text) {
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

/// `word` as an absolute path ("@LIST" keeps its '@').
std::string absolute_input(const std::string& word, const std::filesystem::path& cwd,
                           std::vector<std::filesystem::path>& inputs) {
  const bool list = word.size() > 1 && word.front() == '@';
  const std::filesystem::path path = list ? word.substr(1) : word;
  const std::filesystem::path absolute = (cwd / path).lexically_normal();
  inputs.push_back(absolute);
  std::string text = absolute.string();
  if (word.size() > 1 && word.back() == '/' && text.back() != '/') text += '/';
  return list ? "@" + text : text;
}

/// Where the command is, for messages: "tumble render".
std::string command_label(const std::string& name) {
  return "tumble " + name;
}

/// The index of the command's name in `words`, after an optional "tumble" or path to one.
std::size_t command_start(const std::vector<std::string>& words, std::filesystem::path& tumble) {
  if (words.empty()) throw InputError("no tumble command after '--'");
  if (find_command(words[0]) != nullptr) return 0;
  const std::filesystem::path first = words[0];
  if (first.filename() != "tumble") {
    throw InputError("'" + words[0] +
                     "': expected a tumble command after '--': render, compare, bench, "
                     "stability or inspect");
  }
  if (words[0] != "tumble") tumble = first;
  if (words.size() < 2) throw InputError("no tumble command after '" + words[0] + "'");
  return 1;
}

}  // namespace

const std::vector<FarmedCommand>& farmed_commands() {
  static const std::vector<FarmedCommand> commands = {
      {"render", video_options({{"--integrator", true},
                                {"--dt", true},
                                {"--aa", true},
                                {"--no-overlay", false},
                                {"--from", true},
                                {"--package-path", true}})},
      {"compare", video_options({{"--integrators", true}, {"--layout", true}, {"--dt", true}})},
      {"bench",
       {{"--integrators", true},
        {"--dts", true},
        {"--tolerances", true},
        {"--duration", true},
        {"--repeat", true},
        {"--jobs", true}}},
      {"stability",
       {{"--suite", true},
        {"--integrators", true},
        {"--dts", true},
        {"--cases", true},
        {"--list-suites", false}}},
      {"inspect",
       {{"--format", true},
        {"--json", false},
        {"--jsonl", false},
        {"--frame", true},
        {"-r,--recursive", false},
        {"--jobs", true},
        {"--density", true},
        {"--mass", true},
        {"--scale", true},
        {"--shell", true},
        {"--overlap", true},
        {"--inertia", true},
        {"--allow-overlap", false},
        {"--skip-overlap-checks", false}}},
  };
  return commands;
}

namespace {

/// Splits "--name=value" and "-xVALUE" into the option's name and its attached value.
std::string_view option_name(std::string_view word, std::string& attached, bool& has_attached) {
  has_attached = false;
  if (word.substr(0, 2) == "--") {
    const std::size_t equals = word.find('=');
    if (equals == std::string_view::npos) return word;
    attached = std::string(word.substr(equals + 1));
    has_attached = true;
    return word.substr(0, equals);
  }
  if (word.size() > 2) {
    attached = std::string(word.substr(2));
    has_attached = true;
  }
  return word.substr(0, 2);
}

struct CommandReader {
  const FarmedCommand& command;
  const std::filesystem::path& cwd;
  std::string where;
  FarmJob job;
  std::string output;
  bool has_output = false;

  void option(const std::vector<std::string>& words, std::size_t& i) {
    std::string attached;
    bool has_attached = false;
    const std::string name(option_name(words[i], attached, has_attached));
    if (name == "--shard") {
      throw InputError(where + ": already has --shard; give the whole command: tumble farm " +
                       "adds --shard I/N to each part");
    }
    const bool is_output = name == "-o" || name == "--output";
    const FarmedOption* known = is_output ? nullptr : find_option(command, name);
    if (!is_output && known == nullptr) {
      throw InputError(where + ": unknown option '" + name + "' (see " + where + " --help)");
    }
    if (!is_output && !known->takes_value) {
      if (has_attached) {
        throw InputError(where + ": option '" + name + "' takes no value, got '" + words[i] + "'");
      }
      job.args.push_back(words[i]);
      return;
    }
    std::string value = attached;
    if (!has_attached) {
      if (i + 1 >= words.size()) throw InputError(where + ": option '" + name + "' needs a value");
      value = words[++i];
    }
    if (!is_output) {
      job.args.push_back(name);
      job.args.push_back(value);
      return;
    }
    if (has_output) throw InputError(where + ": -o is given twice");
    has_output = true;
    output = value;
  }
};

}  // namespace

FarmJob parse_farm_job(const std::vector<std::string>& words, const std::filesystem::path& cwd) {
  std::filesystem::path tumble;
  const std::size_t start = command_start(words, tumble);
  const FarmedCommand* command = find_command(words[start]);
  if (command == nullptr) {
    throw InputError("'tumble " + words[start] +
                     "' cannot be farmed: expected render, compare, bench, stability or inspect");
  }
  CommandReader reader{*command, cwd, command_label(words[start]), {}, {}, false};
  reader.job.command = words[start];
  reader.job.tumble = tumble.empty() ? tumble : (cwd / tumble).lexically_normal();
  bool positional_only = false;
  for (std::size_t i = start + 1; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word.find('\n') != std::string::npos) {
      throw InputError(reader.where +
                       ": a word holds a newline, which the job scripts cannot "
                       "carry");
    }
    if (!positional_only && word == "--") {
      positional_only = true;
      reader.job.args.push_back(word);
    } else if (!positional_only && word.size() > 1 && word.front() == '-') {
      reader.option(words, i);
    } else {
      reader.job.args.push_back(absolute_input(word, cwd, reader.job.inputs));
    }
  }
  if (!reader.has_output) {
    throw InputError(reader.where + ": no -o OUT; a farmed job needs an output to merge into");
  }
  const std::filesystem::path output = cwd / reader.output;
  std::error_code error;
  const bool directory = std::filesystem::is_directory(output, error);
  reader.job.form = output_form(reader.job.command, reader.output, directory, reader.where);
  reader.job.output = without_trailing_slashes(output.lexically_normal().string());
  return reader.job;
}

std::filesystem::path parts_folder(const FarmJob& job) {
  return job.output.string() + ".parts";
}

std::string part_file_name(const FarmJob& job, std::string_view index) {
  const std::string stem = "part-" + std::string(index);
  switch (job.form) {
    case PartForm::kVideo:
      return stem + lower(job.output.extension().string());
    case PartForm::kPngFolder:
      return stem + "/";
    case PartForm::kRowsFolder:
      return stem;
    case PartForm::kJsonLines:
      return stem + ".jsonl";
  }
  return stem;
}

}  // namespace tumble::app
