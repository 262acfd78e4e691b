// PartKind::check of the render and compare parts (app/video_parts), on parts written in process
// by write_render --shard: a whole part passes; a part that lost a frame, holds another's, has a
// PNG cut short or a segment cut short fails in one line naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "app/farm/part_manifest.hpp"
#include "app/video/render_job.hpp"
#include "app/video_parts/video_merge.hpp"
#include "media/output_kind.hpp"
#include "support/command_test.hpp"
#include "support/input_error.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class VideoPartCheck : public testing::CommandTest {
 protected:
  /// Shard `shard` of frames 0:4 of a tumbling brick at 1 frame/s (a key frame every 2 frames),
  /// written to `name`; its manifest read back.
  NamedManifest part(const std::string& shard, const std::string& name) const {
    RenderOptions options;
    options.scene = path("scene.json");
    if (!fs::exists(options.scene)) write_scene(testing::tumbling_scene(4.0, 0.01));
    options.size = "32x24";
    options.fps = 1.0;
    options.frames = "0:4";
    options.shard = shard;
    options.quiet = true;
    options.output = path(name);
    std::ostringstream out, err;
    EXPECT_EQ(write_render(options, nullptr, out, err, false), 0) << err.str();
    return {options.output, read_part_manifest(options.output)};
  }

  /// The message of render_parts().check(`named`)'s InputError.
  static std::string refusal(const NamedManifest& named) {
    return testing::input_error_of([&] { render_parts().check(named); }, named.part.string());
  }
};

TEST_F(VideoPartCheck, AWholePngPartPassesAndALostStrayOrCutFrameIsNamed) {
  const NamedManifest second = part("1/2", "part-1/");
  EXPECT_EQ(second.manifest.kind, "render");
  EXPECT_NO_THROW(render_parts().check(second));
  EXPECT_EQ(&render_parts(), &render_parts());
  EXPECT_NE(compare_parts().name(), render_parts().name());

  const fs::path three = dir_ / "part-1" / media::frame_file_name(3);
  const fs::path kept = path("kept.png");
  fs::copy_file(three, kept);
  fs::resize_file(three, fs::file_size(three) - 5);  // cut short: the IEND chunk's CRC lost
  EXPECT_EQ(refusal(second), three.string() +
                                 ": not a whole PNG file (cut short?); render the part of frames "
                                 "2:4 again");
  fs::remove(three);
  EXPECT_EQ(refusal(second),
            second.part.string() + ": frame_000003.png missing (the part is frames 2:4)");
  fs::copy_file(kept, three);
  fs::copy_file(kept, dir_ / "part-1" / media::frame_file_name(1));  // another shard's frame
  EXPECT_EQ(refusal(second),
            second.part.string() + ": frame_000001.png is not one of its frames 2:4");
}

TEST_F(VideoPartCheck, ASegmentCutShortIsNamed) {
  const NamedManifest first = part("0/2", "part-0.mp4");
  EXPECT_NO_THROW(render_parts().check(first));
  fs::resize_file(first.part, fs::file_size(first.part) / 2);
  const std::string message = refusal(first);
  EXPECT_THAT(message, ::testing::StartsWith(first.part.string() + ": "));
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace tumble::app
