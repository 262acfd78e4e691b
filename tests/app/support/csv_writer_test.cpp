// CSV fields and numbers (RFC 4180, 17 significant digits), the atomic file and the
// trajectory CSV written through it.
#include "app/support/csv_writer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "base/temporary_path.hpp"
#include "support/csv_reader.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::input_error_of;
using testing::read_text;

std::string field(std::string_view text) {
  std::string out;
  append_csv_field(out, text);
  return out;
}

std::string number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

TEST(AppendCsvField, PlainTextIsWrittenAsIs) {
  EXPECT_EQ(field("brick"), "brick");
  EXPECT_EQ(field(""), "");
  EXPECT_EQ(field("a b;c\t'd'"), "a b;c\t'd'");
}

TEST(AppendCsvField, CommasQuotesAndLineBreaksAreQuoted) {
  EXPECT_EQ(field("a,b"), "\"a,b\"");
  EXPECT_EQ(field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(field("\""), "\"\"\"\"");
  EXPECT_EQ(field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(field("cr\rhere"), "\"cr\rhere\"");
}

TEST(AppendCsvField, AppendsToWhatIsThere) {
  std::string out = "1,";
  append_csv_field(out, "x,y");
  EXPECT_EQ(out, "1,\"x,y\"");
}

TEST(AppendCsvField, EveryFieldReadsBackThroughAnRfc4180Reader) {
  const std::vector<std::string> fields = {"plain", "a,b", "q\"uote", "line\nbreak", "", "\"\""};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    append_csv_field(line, fields[i]);
  }
  line += '\n';
  const auto records = testing::parse_csv_records(line);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0], fields);
}

TEST(AppendNumber, SeventeenSignificantDigitsReadBackExactly) {
  EXPECT_EQ(number(0.1), "0.10000000000000001");
  EXPECT_EQ(number(1.0), "1");
  EXPECT_EQ(number(-2.5), "-2.5");
  EXPECT_EQ(number(1e-300), "1e-300");
  EXPECT_EQ(number(1.0 / 3.0), "0.33333333333333331");  // as printf("%.17g") writes them
  EXPECT_EQ(number(4.9e-324), "4.9406564584124654e-324");
  EXPECT_EQ(number(123456789.0), "123456789");
  for (const double value :
       {1.0 / 3.0, M_PI, -std::exp(1.0) * 1e200, 4.9e-324, std::numeric_limits<double>::max()}) {
    EXPECT_EQ(std::strtod(number(value).c_str(), nullptr), value) << number(value);
  }
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("AtomicFileTest"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFileTest, NothingUnderTheFinalNameUntilCommitted) {
  const fs::path target = dir_ / "out.csv";
  AtomicFile file(target);
  EXPECT_EQ(file.path(), target);
  EXPECT_EQ(file.temporary_path(), dir_ / (".out.csv.tmp-" + std::to_string(::getpid())));
  EXPECT_TRUE(fs::exists(file.temporary_path()));
  file.write("a,b\n");
  file.write("1,2\n");
  EXPECT_FALSE(fs::exists(target));
  file.commit();
  EXPECT_EQ(read_text(target), "a,b\n1,2\n");
  EXPECT_FALSE(fs::exists(file.temporary_path()));
  EXPECT_THAT(testing::directory_entries(dir_), ElementsAre("out.csv"));
}

TEST_F(AtomicFileTest, CommitReplacesAnEarlierFileOnlyAtTheEnd) {
  const fs::path target = dir_ / "out.csv";
  { std::ofstream(target) << "old\n"; }
  AtomicFile file(target);
  file.write("new\n");
  EXPECT_EQ(read_text(target), "old\n");
  file.commit();
  EXPECT_EQ(read_text(target), "new\n");
}

TEST_F(AtomicFileTest, DestroyedUncommittedRemovesTheTemporaryAndKeepsTheOldFile) {
  const fs::path target = dir_ / "kept.csv";
  { std::ofstream(target) << "old\n"; }
  fs::path temporary;
  {
    AtomicFile file(target);
    temporary = file.temporary_path();
    file.write("half a fi");
    EXPECT_TRUE(fs::exists(temporary));
  }
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(read_text(target), "old\n");
  EXPECT_THAT(testing::directory_entries(dir_), ElementsAre("kept.csv"));
}

TEST_F(AtomicFileTest, DestroyedUncommittedLeavesNothingWhenThereWasNoFile) {
  { AtomicFile file(dir_ / "never.csv"); }
  EXPECT_TRUE(testing::directory_entries(dir_).empty());
}

TEST_F(AtomicFileTest, AMissingFolderIsAnInputErrorNamingThePath) {
  const fs::path target = dir_ / "missing" / "out.csv";
  const std::string message = input_error_of([&] { AtomicFile file(target); });
  EXPECT_THAT(message, HasSubstr("cannot write '" + target.string() + "'"));
  EXPECT_THAT(message, HasSubstr("No such file or directory"));
}

TEST_F(AtomicFileTest, ADirectoryIsAnInputErrorNamingIt) {
  EXPECT_EQ(input_error_of([&] { AtomicFile file(dir_); }),
            "cannot write '" + dir_.string() +
                "': it is a directory, not a regular file (it is never replaced)");
  EXPECT_TRUE(testing::directory_entries(dir_).empty());
}

TEST_F(AtomicFileTest, APathBelowARegularFileIsAnInputErrorNamingIt) {
  { std::ofstream(dir_ / "plain") << "x"; }
  const fs::path target = dir_ / "plain" / "out.csv";
  EXPECT_THAT(input_error_of([&] { AtomicFile file(target); }),
              HasSubstr("cannot write '" + target.string() + "': Not a directory"));
}

TEST_F(AtomicFileTest, WritingOrCommittingAgainAfterCommitIsAnError) {
  const fs::path target = dir_ / "once.csv";
  AtomicFile file(target);
  file.write("x");
  file.commit();
  EXPECT_THAT(input_error_of([&] { file.write("y"); }),
              HasSubstr("cannot write '" + target.string() + "': file is closed"));
  EXPECT_EQ(read_text(target), "x");
}

TEST_F(AtomicFileTest, AFullDiskIsAnInputErrorAndLeavesNoTemporary) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  // A symlink as the temporary's name sends the writes to /dev/full: fwrite buffers, so the
  // error shows at commit's flush.
  const fs::path target = dir_ / "full.csv";
  fs::create_symlink("/dev/full", tumble::temporary_sibling(target));
  const std::string message = input_error_of([&] {
    AtomicFile file(target);
    file.write(std::string(1 << 16, 'x'));
    file.commit();
  });
  EXPECT_THAT(message, HasSubstr("cannot write '" + target.string() + "': write failed"));
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(testing::directory_entries(dir_).empty());
}

TEST(TrajectoryCsv, HeaderAndOneRowPerBodyRoundTrip) {
  const fs::path dir = testing::fresh_directory("TrajectoryCsv");
  const fs::path target = dir / "trajectory.csv";
  engine::BodyModel plain;
  plain.name = "brick";
  plain.mass = 2.0;
  plain.moments = {1.0, 2.0, 4.0};
  engine::BodyModel awkward = plain;
  awkward.name = "a \"quoted\", name";
  engine::BodyState state;
  state.position = {1.0, -2.0, 0.1};
  state.velocity = {0.5, 0.0, -0.25};
  state.angular_momentum = {1.0, 2.0, 4.0};  // w = (1, 1, 1) with the identity orientation
  {
    TrajectoryCsv csv(target);
    csv.write_rows(0.0, {plain, awkward}, {state, state});
    csv.write_rows(0.1, {plain, awkward}, {state, state});
    EXPECT_EQ(csv.rows(), 4u);
    EXPECT_FALSE(fs::exists(target));
    csv.commit();
  }
  const testing::CsvTable table = testing::read_csv(target);
  EXPECT_EQ(table.header, testing::csv_fields(std::string(kTrajectoryHeader)));
  ASSERT_EQ(table.records.size(), 4u);
  EXPECT_EQ(table.rows[1].at("body"), "a \"quoted\", name");
  EXPECT_EQ(table.rows[2].at("t"), "0.10000000000000001");
  const auto& row = table.rows[3];
  EXPECT_EQ(row.at("x"), "1");
  EXPECT_EQ(row.at("y"), "-2");
  EXPECT_EQ(std::stod(row.at("z")), 0.1);
  EXPECT_EQ(row.at("qw"), "1");
  EXPECT_EQ(row.at("vz"), "-0.25");
  EXPECT_EQ(row.at("wx"), "1");
  EXPECT_EQ(row.at("wy"), "1");
  EXPECT_EQ(row.at("wz"), "1");
  EXPECT_EQ(row.at("Lz"), "4");
  // E = m v^2 / 2 + w . L / 2 = 2 * 0.3125 / 2 + 7 / 2 = 3.8125.
  EXPECT_EQ(row.at("energy"), "3.8125");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tumble::app
