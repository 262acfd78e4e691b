// gnuplot's pictures checked whole: gnuplot exits 0 when its output is cut short (a full disk),
// so a PNG must end with its IEND chunk and an SVG with its closing tag.
#include "app/analysis/gnuplot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/support/file_write.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);
const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);

class CheckPictures : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("CheckPictures"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  /// The message of the WriteError check_pictures throws for `pictures` (empty: none thrown).
  static std::string error_of(const std::vector<fs::path>& pictures) {
    try {
      check_pictures(pictures);
    } catch (const WriteError& error) {
      return error.what();
    }
    return {};
  }
  fs::path dir_;
};

TEST_F(CheckPictures, WholePngAndSvgPass) {
  const fs::path png = file("a.png", kPngSignature + std::string(5000, 'p') + kIend);
  const fs::path svg = file("a.svg", "<svg>\n<g>\n</g>\n</svg>\n\n");
  EXPECT_EQ(error_of({png, svg}), "");
}

TEST_F(CheckPictures, ACutPngIsNamed) {
  const fs::path svg = file("a.svg", "<svg>\n</svg>\n");
  const fs::path png = file("a.png", kPngSignature + std::string(4088, 'p'));
  EXPECT_EQ(error_of({svg, png}), "cannot write '" + png.string() +
                                      "': gnuplot stopped after 4096 bytes, the picture is "
                                      "incomplete (is the disk full?)");
}

TEST_F(CheckPictures, ACutOrMissingSvgIsNamed) {
  const fs::path svg = file("a.svg", "<svg>\n<g>\n<path d='M 1 2 L");
  EXPECT_THAT(error_of({svg}), HasSubstr("cannot write '" + svg.string() + "': gnuplot stopped"));
  EXPECT_EQ(error_of({dir_ / "b.svg"}), "cannot write '" + (dir_ / "b.svg").string() +
                                            "': gnuplot wrote no picture (is the disk full?)");
}

}  // namespace
}  // namespace tumble::app
