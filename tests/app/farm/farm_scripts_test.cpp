// The job scripts of tumble farm: bash itself reads back every quoted word (the oracle for the
// quoting), and the Slurm and GNU parallel texts hold the array range, resources, dependency and
// part names.
#include "app/farm/farm_scripts.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>
#include <vector>

#include "base/process.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using Words = std::vector<std::string>;
using ::testing::HasSubstr;
using ::testing::Not;

/// The words bash makes of `line` (run with `bash -c`, after `prelude`), as `args` prints them.
Words bash_words(const std::string& line, const std::string& prelude = "") {
  const ProcessResult result =
      run_process({"bash", "-c", prelude + "args() { printf '%s\\0' \"$@\"; }; args " + line});
  EXPECT_EQ(result.status, 0) << result.err;
  Words words;
  std::string word;
  for (const char c : result.out) {
    if (c == '\0') {
      words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  return words;
}

TEST(FarmScripts, BashReadsEveryQuotedWordBackAsItWas) {
  const Words words = {"plain",  "/a/b.json",  "with space", "it's",   "\"double\"", "$HOME",
                       "`ls`",   "a\\b",       "*.json",     "{0..3}", "tab\there",  "",
                       "!event", "semi;colon", "--size=3x4", "%A_%a",  "'"};
  std::string line;
  for (const std::string& word : words) line += shell_quote(word) + " ";
  EXPECT_EQ(bash_words(line), words);
  EXPECT_EQ(shell_quote("/a/b-c_d.json"), "/a/b-c_d.json");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
}

FarmJob render_job() {
  return parse_farm_job(
      {"tumble", "render", "my scenes/it's.json", "--size", "320x180", "-o", "out dir/demo.mp4"},
      "/w");
}

TEST(FarmScripts, AShardCommandIsTheWholeCommandPlusShardAndItsPart) {
  const std::string command =
      shard_command(render_job(), "/opt/tumble app/tumble", "\"$SLURM_ARRAY_TASK_ID\"", 4);
  EXPECT_EQ(bash_words(command, "SLURM_ARRAY_TASK_ID=3; "),
            (Words{"/opt/tumble app/tumble", "render", "/w/my scenes/it's.json", "--size",
                   "320x180", "--shard", "3/4", "-o", "/w/out dir/demo.mp4.parts/part-3.mp4"}));
}

TEST(FarmScripts, TheMergeTakesEveryPartInShardOrder) {
  EXPECT_EQ(bash_words(merge_command(render_job(), "/t/tumble", 3)),
            (Words{"/t/tumble", "merge", "/w/out dir/demo.mp4.parts/part-0.mp4",
                   "/w/out dir/demo.mp4.parts/part-1.mp4", "/w/out dir/demo.mp4.parts/part-2.mp4",
                   "-o", "/w/out dir/demo.mp4"}));
  EXPECT_EQ(bash_words(merge_command(render_job(), "/t/tumble", 1)),
            (Words{"/t/tumble", "merge", "/w/out dir/demo.mp4.parts/part-0.mp4", "-o",
                   "/w/out dir/demo.mp4"}));
  const FarmJob frames = parse_farm_job({"render", "s.json", "-o", "frames/"}, "/w");
  EXPECT_EQ(bash_words(merge_command(frames, "/t/tumble", 2)),
            (Words{"/t/tumble", "merge", "/w/frames.parts/part-0/", "/w/frames.parts/part-1/", "-o",
                   "/w/frames/"}));
}

TEST(FarmScripts, TheArrayScriptHasTheRangeTheResourcesAndTheTask) {
  SlurmResources resources;
  resources.partition = "short";
  resources.time = "0-01:30:00";
  resources.cpus_per_task = 2;
  resources.mem = "4G";
  resources.account = "proj-7";
  resources.max_running = 3;
  const std::string script = slurm_array_script(render_job(), "/t/tumble", 8, resources);
  EXPECT_THAT(script, ::testing::StartsWith("#!/bin/bash\n"));
  for (const char* line :
       {"\n#SBATCH --job-name=tumble-render-demo.mp4\n", "\n#SBATCH --array=0-7%3\n",
        "\n#SBATCH --partition=short\n", "\n#SBATCH --time=0-01:30:00\n",
        "\n#SBATCH --cpus-per-task=2\n", "\n#SBATCH --mem=4G\n", "\n#SBATCH --account=proj-7\n"}) {
    EXPECT_THAT(script, HasSubstr(line));
  }
  const std::string task =
      "\nexec " + shard_command(render_job(), "/t/tumble", "\"$SLURM_ARRAY_TASK_ID\"", 8) + "\n";
  EXPECT_THAT(script, ::testing::EndsWith(task));
  // #SBATCH lines come before the first command, or sbatch ignores them.
  EXPECT_LT(script.rfind("#SBATCH"), script.find("\nexec "));
  const std::string merge = slurm_merge_script(render_job(), "/t/tumble", 8, resources);
  EXPECT_THAT(merge, HasSubstr("#SBATCH --job-name=tumble-render-demo.mp4-merge\n"));
  EXPECT_THAT(merge, HasSubstr("#SBATCH --partition=short\n"));
  EXPECT_THAT(merge, Not(HasSubstr("--array")));
  EXPECT_THAT(merge, Not(HasSubstr("--cpus-per-task")));
  EXPECT_THAT(merge,
              ::testing::EndsWith("\nexec " + merge_command(render_job(), "/t/tumble", 8) + "\n"));
  EXPECT_THAT(slurm_array_script(render_job(), "/t/tumble", 1, {}), HasSubstr("--array=0-0\n"));
}

TEST(FarmScripts, TheSubmitScriptSubmitsTheMergeAfterTheArray) {
  const std::string script = slurm_submit_script(render_job(), "/t/tumble", 2, {});
  EXPECT_THAT(script, HasSubstr("\nmkdir -p -- '/w/out dir/demo.mp4.parts'\n"));
  EXPECT_THAT(script,
              HasSubstr("shards=$(sbatch --parsable '--output=/w/out dir/demo.mp4.parts/slurm-%A_"
                        "%a.out' <<'TUMBLE_SHARDS'\n" +
                        slurm_array_script(render_job(), "/t/tumble", 2, {}) + "TUMBLE_SHARDS\n)"));
  EXPECT_THAT(script, HasSubstr("merge=$(sbatch --parsable --dependency=afterok:\"$shards\" "));
  EXPECT_LT(script.find("TUMBLE_SHARDS\n)"), script.find("--dependency"));
  // Slurm's own patterns stay, a '%' of the path is doubled.
  const FarmJob odd = parse_farm_job({"render", "s.json", "-o", "100%/a.mp4"}, "/w");
  EXPECT_EQ(slurm_log_option(odd, true)[0], "--output=/w/100%%/a.mp4.parts/slurm-%j-merge.out");
  // The script is bash that parses (syntax only: -n).
  const ProcessResult check = run_process({"bash", "-n", "-c", script});
  EXPECT_EQ(check.status, 0) << check.err;
}

TEST(FarmScripts, SlurmResourcesOfTheWrongFormAreOneLineErrors) {
  const auto error_of = [](SlurmResources resources) {
    return tumble::testing::input_error_of([&] { check_slurm_resources(resources); });
  };
  SlurmResources r;
  EXPECT_NO_THROW(check_slurm_resources(r));
  for (const char* good :
       {"30", "10:00", "2:00:00", "1-12", "1-12:30", "1-12:30:00", "UNLIMITED"}) {
    r.time = good;
    EXPECT_NO_THROW(check_slurm_resources(r)) << good;
  }
  r.time = "an hour";
  EXPECT_THAT(error_of(r), ::testing::StartsWith("--time: expected minutes, MM:SS"));
  r = {};
  r.mem = "4GB";
  EXPECT_EQ(error_of(r), "--mem: expected megabytes N or N with K, M, G or T (e.g. 4G), got '4GB'");
  r = {};
  r.partition = "a b";
  EXPECT_THAT(error_of(r), ::testing::StartsWith("--partition: expected partition names"));
  r = {};
  r.job_name = "x\ny";
  EXPECT_THAT(error_of(r), ::testing::StartsWith("--job-name: "));
  r = {};
  r.cpus_per_task = 0;
  EXPECT_EQ(error_of(r), "--cpus-per-task: expected at least 1, got 0");
  r = {};
  r.max_running = 0;
  EXPECT_THAT(error_of(r), ::testing::StartsWith("--max-running: "));
}

TEST(FarmScripts, TheParallelLineRunsTheShardsThenTheMerge) {
  const FarmJob bench = parse_farm_job({"bench", "a b.json", "--duration", "1", "-o", "res"}, "/w");
  const std::string line = parallel_command_line(bench, "/t/tumble", 3, {{}, 2});
  EXPECT_EQ(line,
            "mkdir -p -- /w/res.parts && parallel -q --halt now,fail=1 --jobs 2 /t/tumble bench "
            "'/w/a b.json' --duration 1 --shard '{}/3' -o '/w/res.parts/part-{}' ::: {0..2} && "
            "/t/tumble merge /w/res.parts/part-{0..2} -o /w/res");
  EXPECT_THAT(parallel_command_line(bench, "/t/tumble", 2, {{"node1", "2/node2", ":"}, {}}),
              HasSubstr(" --halt now,fail=1 -S node1,2/node2,: /t/tumble bench"));
  EXPECT_THAT(tumble::testing::input_error_of([&] {
                parallel_command_line(bench, "/t/tumble", 2, {{"a b"}, {}});
              }),
              ::testing::StartsWith("-S: expected host names"));
  const FarmJob braces = parse_farm_job({"bench", "{x}.json", "-o", "res"}, "/w");
  EXPECT_THAT(
      tumble::testing::input_error_of([&] { parallel_command_line(braces, "/t/tumble", 2, {}); }),
      HasSubstr("GNU parallel would take its braces"));
}

TEST(FarmScripts, JobNamesKeepToWhatSlurmTakes) {
  EXPECT_EQ(slurm_job_name(render_job(), {}), "tumble-render-demo.mp4");
  const FarmJob odd = parse_farm_job({"bench", "s.json", "-o", "my res'ults"}, "/w");
  EXPECT_EQ(slurm_job_name(odd, {}), "tumble-bench-my_res_ults");
  SlurmResources named;
  named.job_name = "sweep";
  EXPECT_EQ(slurm_job_name(odd, named), "sweep");
}

}  // namespace
}  // namespace tumble::app
