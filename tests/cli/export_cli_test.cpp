// `coinroll export`'s options for a course page (docs/web.md "A page for a course"), from outside:
// the title, caption, controls and details reach the page as JSON in its options placeholder, and a
// bad value is refused with exit 2, naming the option and the fix, before any page is written.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/run_command.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using coinroll::testing::RunResult;

constexpr char kOptionsOpen[] = R"(<script type="application/json" id="coinroll-page-options">)";

class ExportCli : public coinroll::testing::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    std::ofstream(dir_ / "scene.json") << R"({"name": "tilt", "coin": {"radius": 0.0375, "mass": 0.4}, )"
                                          R"("initial": {"theta": 20, "omega_Z": 12}, "duration": 0.2})";
    // A page as tools/build_page.sh leaves it, with three controls in two groups.
    std::ofstream(dir_ / "page.html")
        << R"(<html><script type="application/json" id="coinroll-scene">null</script>)" << kOptionsOpen
        << R"(null</script><script type="application/json" id="coinroll-controls">[{"group": "initial", "title": )"
        << R"("Start", "keys": ["initial.theta", "initial.omega_Z"]}, {"group": "floor", "title": "Floor contact", )"
        << R"("keys": ["friction"]}]</script><script>start()</script></html>)";
  }

  RunResult exportWith(const std::string& options) const {
    return coinroll::testing::runCoinroll("export scene.json -q -o o.html " + options,
                                          "cd " + dir_.string() + " && COINROLL_PAGE=page.html");
  }

  // The options JSON in the written page, and whether it holds a raw '<'.
  nlohmann::json optionsInPage(bool& rawLessThan) const {
    std::ifstream in(dir_ / "o.html");
    const std::string html{std::istreambuf_iterator<char>(in), {}};
    const std::size_t from = html.find(kOptionsOpen);
    if (from == std::string::npos) return nullptr;
    const std::string json =
        html.substr(from + sizeof kOptionsOpen - 1, html.find("</script>", from) - from - (sizeof kOptionsOpen - 1));
    rawLessThan = json.find('<') != std::string::npos;
    return nlohmann::json::parse(json);
  }
};

TEST_F(ExportCli, TitleCaptionControlsAndDetailsReachThePage) {
  const RunResult result = exportWith(
      "--title 'Rolling <i>on</i>' --caption 'Try <b>it</b> </script><!-- <script>' --controls friction,initial.theta "
      "--details shown");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  bool rawLessThan = true;
  const nlohmann::json options = optionsInPage(rawLessThan);
  EXPECT_FALSE(rawLessThan) << "a '<' in the options could end their <script> element";
  EXPECT_EQ(options["title"], "Rolling <i>on</i>");
  EXPECT_EQ(options["caption"], "Try <b>it</b> </script><!-- <script>");
  EXPECT_EQ(options["controls"], nlohmann::json::array({"initial.theta", "friction"})) << "in the page's order";
  EXPECT_EQ(options["details"], "shown");
}

TEST_F(ExportCli, WithoutOptionsThePageIsTitledByTheSceneWithEveryControlAndTheDetailsFolded) {
  const RunResult result = exportWith("");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  bool rawLessThan = true;
  EXPECT_EQ(optionsInPage(rawLessThan),
            nlohmann::json::parse(R"({"title": "tilt", "caption": null, "controls": null, "details": "folded"})"));
  ASSERT_EQ(exportWith("--controls all,floor").exitCode, 0);
  EXPECT_EQ(optionsInPage(rawLessThan)["controls"], nullptr) << "all is every control";
  ASSERT_EQ(exportWith("--controls initial").exitCode, 0);
  EXPECT_EQ(optionsInPage(rawLessThan)["controls"], nlohmann::json::array({"initial.theta", "initial.omega_Z"}));
}

TEST_F(ExportCli, BadPageOptionsExitTwoNameTheOptionAndWriteNoPage) {
  struct Bad {
    std::string options;
    std::string message;
  };
  const std::vector<Bad> bads = {
      {"--controls initial.thet",
       "--controls initial.thet: no such control on the page; did you mean initial.theta? give control keys as the "
       "page's tooltips name them (initial.theta, initial.omega_Z, friction) or a group (all, initial, floor), "
       "separated by commas"},
      {"--controls floo", "--controls floo: no such control on the page; did you mean floor? give"},
      {"--controls coin.radius", "--controls coin.radius: no such control on the page; give"},
      {"--controls initial.theta,", "--controls initial.theta,: an empty name between commas"},
      {"--controls ''", "--controls: empty; give control keys"},
      {"--title ''", "--title: empty; give the page's heading as one line of text"},
      {"--caption " + std::string(1001, 'x'), "--caption: 1001 characters, more than 1000"},
      {"--details open", "--details open: must be folded (one click away) or shown"},
  };
  for (const Bad& bad : bads) {
    const RunResult result = exportWith(bad.options);
    EXPECT_EQ(result.exitCode, 2) << bad.options << ": " << result.output;
    EXPECT_NE(result.output.find("coinroll: error: " + bad.message), std::string::npos)
        << bad.options << ": " << result.output;
    EXPECT_FALSE(fs::exists(dir_ / "o.html")) << bad.options << " left a page";
  }
}

// The page the build makes (tools/build_page.sh), where there is one: every group it declares is
// taken, so every key of its control list is one of the scene schema's.
TEST_F(ExportCli, TheBuiltPagesControlListIsTheSchemas) {
  const fs::path built = fs::path(COINROLL_BINARY_DIR) / "web" / "coinroll.html";
  if (!fs::exists(built)) GTEST_SKIP() << built << " is not built (tools/build_page.sh)";
  const RunResult result =
      coinroll::testing::runCoinroll("export scene.json -q -o o.html --controls coin,initial,floor,flight,effects,run",
                                     "cd " + dir_.string() + " && COINROLL_PAGE=" + built.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  bool rawLessThan = true;
  EXPECT_GT(optionsInPage(rawLessThan)["controls"].size(), 30U);
}

}  // namespace
