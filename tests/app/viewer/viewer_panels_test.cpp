// The viewer's panels without a window: a Dear ImGui context of the test's own (no drawing),
// the panels built into it, and clicks on their buttons fed as the window would feed them.
// What a click does is checked on the Viewer and its Session.
#include "app/viewer/viewer_panels.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

// tumble_viewer links ImGui privately, so its include directory does not reach the tests.
#include <imgui/imgui.h>
#include <imgui/imgui_internal.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/viewer_input.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app::viewer {
namespace {

constexpr int kViewerPanelsWidth = 1024;
constexpr int kViewerPanelsHeight = 720;

class ViewerPanels : public testing::CommandTest {
 protected:
  static void SetUpTestSuite() {
    render::RendererOptions options;
    options.width = 320;
    options.height = 240;
    renderer_ = std::make_unique<render::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer_.reset(); }

  void SetUp() override {
    CommandTest::SetUp();
    context_ = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize =
        ImVec2(static_cast<float>(kViewerPanelsWidth), static_cast<float>(kViewerPanelsHeight));
    unsigned char* pixels = nullptr;
    int width = 0;
    int height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    configure_imgui_keys(io);
    viewer_ = std::make_unique<Viewer>(*renderer_, dir_);
  }
  void TearDown() override {
    viewer_.reset();
    ImGui::DestroyContext(context_);
    CommandTest::TearDown();
  }

  void open_brick() {
    const std::string scene =
        write_scene(testing::SceneBuilder()
                        .duration(5.0)
                        .dt(0.01)
                        .body(testing::BodyBuilder("brick").angular_velocity({0.1, 2.0, 0.1}))
                        .json());
    ASSERT_TRUE(viewer_->open(scene));
  }

  /// Feeds `events`, then builds one frame of the panels.
  void frame(const std::vector<InputEvent>& events = {}) {
    ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& event : events) input_.feed(io, event);
    io.DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    panels_.draw(*viewer_, {60.0, 16.7}, kViewerPanelsWidth, kViewerPanelsHeight);
    ImGui::EndFrame();
    input_.end_frame(io);
  }

  /// The window `name` as the last frame left it, if it was drawn in it.
  static ImGuiWindow* window(const char* name) {
    ImGuiWindow* found = ImGui::FindWindowByName(name);
    return found != nullptr && found->Active ? found : nullptr;
  }

  /// A point of the control panel over the button `label` (found by moving the pointer over
  /// the panel until ImGui reports it hovered), if the panel shows it.
  std::optional<ImVec2> find_button(const char* label) {
    ImGuiWindow* panel = window("tumble view");
    if (panel == nullptr) return std::nullopt;
    return find_item(panel, ImHashStr(label, 0, panel->ID));
  }

  /// A point of `panel` over the item `id`, if it shows it.
  std::optional<ImVec2> find_item(ImGuiWindow* panel, ImGuiID id) {
    for (float y = panel->Pos.y + 2.0f; y < panel->Pos.y + panel->Size.y; y += 4.0f) {
      for (float x = panel->Pos.x + 4.0f; x < panel->Pos.x + panel->Size.x; x += 6.0f) {
        frame({MouseMoveEvent{x, y}});
        if (ImGui::GetCurrentContext()->HoveredId == id) return ImVec2(x, y);
      }
    }
    return std::nullopt;
  }

  /// Clicks the button `label` of the control panel (a test failure when it is not shown).
  void click(const char* label) {
    const std::optional<ImVec2> at = find_button(label);
    ASSERT_TRUE(at.has_value()) << "no button " << label;
    frame({MouseButtonEvent{0, true, at->x, at->y}});
    frame({MouseButtonEvent{0, false, at->x, at->y}});
    frame();
  }

  static std::unique_ptr<render::Renderer> renderer_;
  ImGuiContext* context_ = nullptr;
  ImGuiInput input_;
  Panels panels_;
  std::unique_ptr<Viewer> viewer_;
};
std::unique_ptr<render::Renderer> ViewerPanels::renderer_;

TEST_F(ViewerPanels, TheControlPanelFillsTheRightEdgeBelowAMargin) {
  open_brick();
  frame();
  ImGuiWindow* panel = window("tumble view");
  ASSERT_NE(panel, nullptr);
  EXPECT_FLOAT_EQ(panel->Pos.x, kViewerPanelsWidth - kPanelWidth - 10.0f);
  EXPECT_FLOAT_EQ(panel->Pos.y, 10.0f);
  EXPECT_FLOAT_EQ(panel->Size.x, kPanelWidth);
  EXPECT_FLOAT_EQ(panel->Size.y, kViewerPanelsHeight - 20.0f);
}

TEST_F(ViewerPanels, ThePanelFollowsTheTextSize) {
  // 20 px text (a 1920x1080 window's): 360 x 20 / 13 = 553 px wide would pass 45 % of the
  // 1024 px width, so the panel is 460 px; margins round(10 x 20 / 13) = 15 px.
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  ImFontConfig config;
  config.SizePixels = 20.0f;
  io.FontDefault = io.Fonts->AddFontDefault(&config);
  unsigned char* pixels = nullptr;
  int width = 0;
  int height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  open_brick();
  frame();
  ImGuiWindow* panel = window("tumble view");
  ASSERT_NE(panel, nullptr);
  EXPECT_EQ(ImGui::GetFontSize(), 20.0f);
  EXPECT_FLOAT_EQ(panel->Size.x, 460.0f);
  EXPECT_FLOAT_EQ(panel->Pos.x, kViewerPanelsWidth - 460.0f - 15.0f);
  EXPECT_FLOAT_EQ(panel->Pos.y, 15.0f);
  EXPECT_FLOAT_EQ(panel->Size.y, kViewerPanelsHeight - 30.0f);
}

TEST_F(ViewerPanels, NothingOpenShowsOnlyTheFilesSectionClosed) {
  frame();
  ASSERT_NE(window("tumble view"), nullptr);
  EXPECT_FALSE(find_button("Step").has_value());
  EXPECT_FALSE(find_button("Reset camera").has_value());
  EXPECT_FALSE(find_button("Open").has_value());  // the Files section starts closed
  click("Files");
  EXPECT_TRUE(find_button("Open").has_value());
}

TEST_F(ViewerPanels, OpenRequestedOpensTheFilesSection) {
  frame();
  viewer_->open_requested = true;  // what Ctrl+O sets
  frame();
  EXPECT_FALSE(viewer_->open_requested);
  EXPECT_TRUE(find_button("Open").has_value());
}

TEST_F(ViewerPanels, TypingAPathAndClickingOpenOpensIt) {
  const std::string scene =
      write_scene(testing::SceneBuilder().name("typed").body(testing::BodyBuilder("brick")).json(),
                  "typed.json");
  frame();
  click("Files");
  click("##open");
  frame({TextEvent{scene}});
  frame();
  click("Open");
  EXPECT_EQ(viewer_->file(), scene);
  EXPECT_EQ(viewer_->session().scene().name, "typed");
}

TEST_F(ViewerPanels, PlayPauseTogglesTheSession) {
  open_brick();
  frame();
  const bool paused = viewer_->session().paused();
  click(paused ? "Play" : "Pause");
  EXPECT_EQ(viewer_->session().paused(), !paused);
  click(paused ? "Pause" : "Play");
  EXPECT_EQ(viewer_->session().paused(), paused);
}

TEST_F(ViewerPanels, StepAdvancesOneDtAndPauses) {
  open_brick();
  frame();
  const double before = viewer_->session().time();
  click("Step");
  EXPECT_TRUE(viewer_->session().paused());
  EXPECT_NEAR(viewer_->session().time(), before + 0.01, 1e-12);
  click("Reset");
  EXPECT_EQ(viewer_->session().time(), 0.0);
}

TEST_F(ViewerPanels, MinusAndPlusHalveAndDoubleTheTimeScale) {
  open_brick();
  frame();
  const double scale = viewer_->session().time_scale();
  click("+");
  EXPECT_DOUBLE_EQ(viewer_->session().time_scale(), 2.0 * scale);
  click("-");
  click("-");
  EXPECT_DOUBLE_EQ(viewer_->session().time_scale(), 0.5 * scale);
}

TEST_F(ViewerPanels, HelpButtonShowsTheKeysWindowAndClosesIt) {
  frame();
  click("Files");
  EXPECT_EQ(window("Keys"), nullptr);
  click("Help (F1)");
  EXPECT_TRUE(viewer_->help_shown);
  EXPECT_NE(window("Keys"), nullptr);
  click("Help (F1)");
  EXPECT_FALSE(viewer_->help_shown);
  EXPECT_EQ(window("Keys"), nullptr);
}

TEST_F(ViewerPanels, AnErrorNoticeIsDismissedByItsButton) {
  viewer_->notify("first, not an error");
  viewer_->notify("bad thing", /*error=*/true);
  frame();
  frame();
  ImGuiWindow* notices = window("notices");
  ASSERT_NE(notices, nullptr);
  // The second notice's button: "dismiss" below PushID(1).
  const int index = 1;
  const ImGuiID id = ImHashStr("dismiss", 0, ImHashData(&index, sizeof index, notices->ID));
  const std::optional<ImVec2> at = find_item(notices, id);
  ASSERT_TRUE(at.has_value());
  frame({MouseButtonEvent{0, true, at->x, at->y}});
  frame({MouseButtonEvent{0, false, at->x, at->y}});
  frame();
  ASSERT_EQ(viewer_->notices().size(), 1u);
  EXPECT_EQ(viewer_->notices()[0].text, "first, not an error");
  // A plain notice has no button.
  const int first = 0;
  EXPECT_FALSE(
      find_item(notices, ImHashStr("dismiss", 0, ImHashData(&first, sizeof first, notices->ID)))
          .has_value());
}

TEST_F(ViewerPanels, NoticesGetAWindowOfTheirOwnAtTheBottomLeft) {
  frame();
  EXPECT_EQ(window("notices"), nullptr);  // nothing to say yet
  viewer_->notify("something went wrong", /*error=*/true);
  frame();
  frame();  // auto-resizing windows settle in their second frame
  ImGuiWindow* notices = window("notices");
  ASSERT_NE(notices, nullptr);
  EXPECT_FLOAT_EQ(notices->Pos.x, 10.0f);
  EXPECT_FLOAT_EQ(notices->Pos.y + notices->Size.y, kViewerPanelsHeight - 10.0f);
}

}  // namespace
}  // namespace tumble::app::viewer
