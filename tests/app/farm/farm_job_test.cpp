// A tumble command read as a farmed job: options by each command's table (held to the real
// commands' CLI11 options), inputs made absolute, the output's form and the parts' names.
#include "app/farm/farm_job.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/bench_command.hpp"
#include "app/commands/compare_command.hpp"
#include "app/commands/inspect_command.hpp"
#include "app/commands/render_command.hpp"
#include "app/commands/stability_command.hpp"
#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using Words = std::vector<std::string>;
using ::testing::HasSubstr;

FarmJob parse(const Words& words) {
  return parse_farm_job(words, "/work/dir");
}

std::string farm_job_error_of(const Words& words) {
  return tumble::testing::input_error_of([&] { parse(words); }, "the command");
}

TEST(FarmJob, ReadsARenderWithItsPathsMadeAbsolute) {
  const FarmJob job = parse({"tumble", "render", "scenes/demo.json", "--size", "320x180",
                             "--fps=24", "-q", "-o", "out/demo.mp4"});
  EXPECT_EQ(job.command, "render");
  EXPECT_EQ(job.args,
            (Words{"/work/dir/scenes/demo.json", "--size", "320x180", "--fps", "24", "-q"}));
  EXPECT_EQ(job.output, "/work/dir/out/demo.mp4");
  EXPECT_EQ(job.form, PartForm::kVideo);
  EXPECT_EQ(job.inputs, (std::vector<std::filesystem::path>{"/work/dir/scenes/demo.json"}));
  EXPECT_TRUE(job.tumble.empty());
  EXPECT_EQ(parts_folder(job), "/work/dir/out/demo.mp4.parts");
  EXPECT_EQ(part_file_name(job, "3"), "part-3.mp4");
  EXPECT_EQ(part_file_name(job, "$SLURM_ARRAY_TASK_ID"), "part-$SLURM_ARRAY_TASK_ID.mp4");
}

TEST(FarmJob, TakesTheCommandWithOrWithoutTumbleOrAPathToIt) {
  EXPECT_EQ(parse({"bench", "a.json", "-o", "b"}).command, "bench");
  const FarmJob job = parse({"../build/app/tumble", "bench", "a.json", "-ob"});
  EXPECT_EQ(job.tumble, "/work/build/app/tumble");
  EXPECT_EQ(job.output, "/work/dir/b");
  EXPECT_EQ(job.form, PartForm::kRowsFolder);
  EXPECT_EQ(part_file_name(job, "0"), "part-0");
  EXPECT_EQ(parse({"tumble", "stability", "--output=/abs/st/"}).output, "/abs/st");
}

TEST(FarmJob, PartsOfEachOutputForm) {
  const FarmJob webm = parse({"compare", "s.json", "--integrators", "rk4,dopri", "-o", "c.WebM"});
  EXPECT_EQ(part_file_name(webm, "1"), "part-1.webm");
  const FarmJob frames = parse({"render", "s.json", "-o", "frames/"});
  EXPECT_EQ(frames.form, PartForm::kPngFolder);
  EXPECT_EQ(frames.output, "/work/dir/frames");
  EXPECT_EQ(part_file_name(frames, "2"), "part-2/");
  EXPECT_EQ(parts_folder(frames), "/work/dir/frames.parts");
  EXPECT_EQ(parse({"render", "s.json", "-o", "a.gif"}).form, PartForm::kPngFolder);
  const FarmJob masses = parse({"inspect", "meshes/", "@list.txt", "-r", "-o", "m.json"});
  EXPECT_EQ(masses.form, PartForm::kJsonLines);
  EXPECT_EQ(masses.args, (Words{"/work/dir/meshes/", "@/work/dir/list.txt", "-r"}));
  EXPECT_EQ(part_file_name(masses, "0"), "part-0.jsonl");
  EXPECT_EQ(part_file_name(parse({"inspect", "x.stl", "-o", "m.jsonl"}), "5"), "part-5.jsonl");
}

TEST(FarmJob, WordsAfterTheCommandsOwnDoubleDashArePaths) {
  const FarmJob job = parse({"inspect", "-o", "m.jsonl", "--", "-odd.stl"});
  EXPECT_EQ(job.args, (Words{"--", "/work/dir/-odd.stl"}));
}

TEST(FarmJob, RefusesWhatCannotBeFarmed) {
  EXPECT_THAT(farm_job_error_of({}), HasSubstr("no tumble command"));
  EXPECT_THAT(farm_job_error_of({"tumble"}), HasSubstr("no tumble command after 'tumble'"));
  EXPECT_THAT(farm_job_error_of({"ls", "-l"}), HasSubstr("'ls': expected a tumble command"));
  EXPECT_THAT(farm_job_error_of({"tumble", "simulate", "s.json"}),
              HasSubstr("'tumble simulate' cannot be farmed"));
  EXPECT_EQ(farm_job_error_of({"render", "s.json", "--shard", "0/2", "-o", "a.mp4"}),
            "tumble render: already has --shard; give the whole command: tumble farm adds "
            "--shard I/N to each part");
  EXPECT_THAT(farm_job_error_of({"render", "s.json", "--shard=0/2", "-o", "a.mp4"}),
              HasSubstr("already has --shard"));
  EXPECT_EQ(farm_job_error_of({"render", "s.json", "--sise", "9x9", "-o", "a.mp4"}),
            "tumble render: unknown option '--sise' (see tumble render --help)");
  EXPECT_EQ(farm_job_error_of({"render", "s.json", "-o"}),
            "tumble render: option '-o' needs a value");
  EXPECT_EQ(farm_job_error_of({"render", "s.json", "--size"}),
            "tumble render: option '--size' needs a value");
  EXPECT_THAT(farm_job_error_of({"render", "s.json", "--no-overlay=1", "-o", "a.mp4"}),
              HasSubstr("option '--no-overlay' takes no value"));
  EXPECT_EQ(farm_job_error_of({"bench", "s.json"}),
            "tumble bench: no -o OUT; a farmed job needs an output to merge into");
  EXPECT_EQ(farm_job_error_of({"bench", "s.json", "-o", "a", "-o", "b"}),
            "tumble bench: -o is given twice");
  EXPECT_THAT(farm_job_error_of({"render", "s.json", "-o", "a.avi"}),
              HasSubstr("-o 'a.avi': expected a .mp4, .webm or .gif file"));
  EXPECT_THAT(farm_job_error_of({"inspect", "x.stl", "-o", "m.csv"}),
              HasSubstr("a farmed inspect writes .jsonl or .json"));
  EXPECT_THAT(farm_job_error_of({"render", "a\nb.json", "-o", "a.mp4"}), HasSubstr("newline"));
}

/// Every option of the real command `name` (its CLI11 definition): names and whether it takes
/// a value, positionals left out.
std::vector<std::pair<std::string, bool>> real_options(const std::string& name) {
  CLI::App cli;
  RenderOptions render;
  CompareOptions compare;
  BenchOptions bench;
  StabilityOptions stability;
  InspectOptions inspect;
  const std::map<std::string, std::function<CLI::App&()>> add = {
      {"render", [&]() -> CLI::App& { return add_render_command(cli, render); }},
      {"compare", [&]() -> CLI::App& { return add_compare_command(cli, compare); }},
      {"bench", [&]() -> CLI::App& { return add_bench_command(cli, bench); }},
      {"stability", [&]() -> CLI::App& { return add_stability_command(cli, stability); }},
      {"inspect", [&]() -> CLI::App& { return add_inspect_command(cli, inspect); }}};
  CLI::App& command = add.at(name)();
  std::vector<std::pair<std::string, bool>> options;
  for (const CLI::Option* option : command.get_options()) {
    if (!option->nonpositional() || option->get_name() == "--help") continue;
    EXPECT_LE(option->get_items_expected_max(), 1)
        << name << " " << option->get_name() << " takes several values: farm reads one";
    for (const std::string& s : option->get_snames()) {
      options.emplace_back("-" + s, option->get_items_expected_max() > 0);
    }
    for (const std::string& l : option->get_lnames()) {
      options.emplace_back("--" + l, option->get_items_expected_max() > 0);
    }
  }
  return options;
}

TEST(FarmJob, KnowsEveryOptionOfTheRealCommands) {
  for (const FarmedCommand& command : farmed_commands()) {
    const std::string name(command.name);
    const std::string output = name == "inspect"                       ? "x.jsonl"
                               : name == "render" || name == "compare" ? "x.mp4"
                                                                       : "x";
    const auto options = real_options(name);
    EXPECT_GE(options.size(), 4u) << name;
    for (const auto& [option, takes_value] : options) {
      if (option == "-o" || option == "--output" || option == "--shard") continue;
      const Words words =
          takes_value ? Words{name, option, "1", "-o", output} : Words{name, option, "-o", output};
      const FarmJob job = parse(words);
      EXPECT_EQ(job.args.size(), takes_value ? 2u : 1u) << name << " " << option;
      EXPECT_TRUE(job.inputs.empty()) << name << " " << option << ": its value taken for a path";
    }
  }
}

}  // namespace
}  // namespace tumble::app
