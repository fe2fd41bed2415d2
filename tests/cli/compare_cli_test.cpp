// `coinroll compare` from outside, as a user's CI runs it: exit 0 same, 1 different, 2 could not
// compare; one line on stdout; the diff image only when asked and never left after bad input.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/run_command.h"
#include "image/image.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using coinroll::image::Image;
using coinroll::testing::RunResult;

class CompareCli : public coinroll::testing::ScratchDirTest {
 protected:
  // A 40x30 opaque picture; `changed` pixels along the top row get +30 in red.
  fs::path writePicture(const std::string& name, int changed = 0, int width = 40, int height = 30) const {
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        std::uint8_t* p = image.pixel(x, y);
        p[0] = static_cast<std::uint8_t>(60 + 3 * x);
        p[1] = static_cast<std::uint8_t>(50 + 4 * y);
        p[2] = 120;
        p[3] = 255;
      }
    }
    for (int x = 0; x < changed; ++x) image.pixel(x, 0)[0] += 30;
    const fs::path path = dir_ / name;
    coinroll::image::writePng(image, path);
    return path;
  }

  RunResult compare(const fs::path& a, const fs::path& b, const std::string& options = "") const {
    return coinroll::testing::runCoinroll("compare " + a.string() + " " + b.string() + " " + options);
  }
};

TEST_F(CompareCli, IdenticalPicturesExitZeroWithInfinitePsnr) {
  const fs::path a = writePicture("a.png"), b = writePicture("b.png");
  const RunResult r = compare(a, b);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("PSNR inf dB, 0 of 1200 pixels differ"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max channel difference 0: SAME"), std::string::npos) << r.output;
}

TEST_F(CompareCli, DifferingPicturesExitOneUnlessWithinTheGivenLimits) {
  const fs::path a = writePicture("a.png"), b = writePicture("b.png", 3);  // 3 of 1200 pixels, 0.25 %
  // MSE over R, G, B of 1200 pixels: 3 * 30^2 / 3600 = 0.75; 10 log10(255^2 / 0.75) = 49.38 dB.
  RunResult r = compare(a, b);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("PSNR 49.38 dB, 3 of 1200 pixels differ (0.25 %"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max channel difference 30: DIFFERENT (3 > --max-differing-pixels 0)"), std::string::npos)
      << r.output;
  EXPECT_EQ(compare(a, b, "--max-differing-pixels 3").exitCode, 0);
  EXPECT_EQ(compare(a, b, "--max-differing-pixels 2").exitCode, 1);
  r = compare(a, b, "--max-differing-fraction 0.01 --min-psnr 30");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("SAME within --max-differing-fraction 0.01, --min-psnr 30"), std::string::npos) << r.output;
  r = compare(a, b, "--max-differing-fraction 0.01 --min-psnr 50");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("DIFFERENT (49.38 dB < --min-psnr 50)"), std::string::npos) << r.output;
  EXPECT_EQ(compare(a, b, "--channel-tolerance 30").exitCode, 0);
  EXPECT_EQ(compare(a, b, "--channel-tolerance 29").exitCode, 1);
}

TEST_F(CompareCli, DiffImageIsWrittenWhenAsked) {
  const fs::path a = writePicture("a.png"), b = writePicture("b.png", 3), diff = dir_ / "diff.png";
  const RunResult r = compare(a, b, "--diff " + diff.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  ASSERT_TRUE(fs::exists(diff)) << r.output;
  const Image picture = coinroll::image::readPng(diff);
  ASSERT_EQ(picture.width, 40);
  ASSERT_EQ(picture.height, 30);
  EXPECT_EQ(picture.pixel(0, 0)[0], 128 + 4 * 29);  // 30 levels off: red
  EXPECT_EQ(picture.pixel(0, 0)[1], 0);
  EXPECT_EQ(picture.pixel(5, 5)[0], picture.pixel(5, 5)[1]);  // equal: grey
  EXPECT_LT(picture.pixel(5, 5)[0], 100);                     // dimmed
  EXPECT_EQ(scratch_->fileCount(), 3) << "a temporary file was left beside the diff";
}

TEST_F(CompareCli, BadInputExitsTwoNamesTheFileAndLeavesNoDiff) {
  const fs::path a = writePicture("a.png"), b = writePicture("b.png", 1), small = writePicture("small.png", 0, 20, 30);
  const fs::path text = dir_ / "text.png";
  std::ofstream(text) << "not a picture\n";
  const fs::path diff = dir_ / "diff.png";
  struct Case {
    std::string arguments, mention;
  };
  const Case cases[] = {
      {(dir_ / "missing.png").string() + " " + b.string(), "missing.png: no such file"},
      {a.string() + " " + text.string(), "text.png: not a PNG"},
      {a.string() + " " + small.string(), "is 40x30 but"},
      {a.string() + " " + dir_.string(), "not a regular file"},
      {a.string() + " " + b.string() + " --channel-tolerance 256", "--channel-tolerance"},
      {a.string() + " " + b.string() + " --max-differing-fraction 1.5", "--max-differing-fraction"},
      {a.string() + " " + b.string() + " --max-differing-pixels -1", "--max-differing-pixels"},
      {a.string(), "b"},  // a second picture is required
  };
  for (const Case& c : cases) {
    const RunResult r = coinroll::testing::runCoinroll("compare " + c.arguments + " --diff " + diff.string());
    EXPECT_EQ(r.exitCode, 2) << c.arguments << ": " << r.output;
    EXPECT_NE(r.output.find(c.mention), std::string::npos) << "message should name '" << c.mention << "': " << r.output;
    EXPECT_FALSE(fs::exists(diff)) << c.arguments;
    EXPECT_EQ(scratch_->fileCount(), 4) << c.arguments;
  }
}

TEST_F(CompareCli, DiffNeverOverwritesAnInputAndMustBeWritable) {
  const fs::path a = writePicture("a.png"), b = writePicture("b.png", 1);
  const std::uintmax_t size = fs::file_size(b);
  RunResult r = compare(a, b, "--diff " + b.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("that is the input"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(b), size);
  r = compare(a, b, "--diff " + (dir_ / "diff.txt").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  r = compare(a, b, "--diff " + (dir_ / "no_such_dir" / "diff.png").string());
  EXPECT_EQ(r.exitCode, 2) << "a diff that cannot be written is not a verdict: " << r.output;
  EXPECT_NE(r.output.find("diff.png"), std::string::npos) << r.output;
  EXPECT_EQ(scratch_->fileCount(), 2);
}

}  // namespace
