// Signals from outside (cli/interrupts.h, docs/outputs.md "Signals"): every request to stop, a
// second one, and one that the work cannot answer in time all end the run with exit 1 and leave
// no file, hidden temporaries included, and earlier files of the same names untouched. SIGKILL,
// which no handler sees, leaves none either where temporaries are unnamed (io/temporary.h).

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "scratch_dir.h"
#include "temporaries.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kEarlierFrame = "an earlier frame, which must survive";

// A coinroll run in the background, started in `directory`, its stderr kept in a file outside it.
class BackgroundRun {
 public:
  BackgroundRun(const fs::path& directory, const std::vector<std::string>& arguments)
      : errors_(fs::temp_directory_path() / ("coinroll_signals_stderr_" + std::to_string(::getpid()))) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const std::string binary = std::string(COINROLL_BINARY_DIR) + "/coinroll";
      const int error = ::open(errors_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (error < 0 || ::dup2(error, STDERR_FILENO) < 0 || ::chdir(directory.c_str()) != 0) ::_exit(127);
      std::vector<char*> argv{const_cast<char*>(binary.c_str())};
      for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
      argv.push_back(nullptr);
      ::execv(binary.c_str(), argv.data());
      ::_exit(127);
    }
  }
  ~BackgroundRun() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ignored;
    fs::remove(errors_, ignored);
  }
  BackgroundRun(const BackgroundRun&) = delete;
  BackgroundRun& operator=(const BackgroundRun&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  // True once the process sleeps in `kernelFunction` (its /proc wchan), within `timeout`: a fixed
  // sleep before a signal is too short on a loaded machine, where the signal then lands before the
  // handlers exist.
  bool reachesKernelWait(std::string_view kernelFunction, std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    const std::string wchan = "/proc/" + std::to_string(pid_) + "/wchan";
    while (std::chrono::steady_clock::now() < deadline) {
      std::string function;
      std::getline(std::ifstream(wchan), function);
      if (function == kernelFunction) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }
  void send(int signal) const { ::kill(pid_, signal); }
  // The wait status (waitpid's), or nothing if the run is still going after `timeout` (a hang).
  std::optional<int> waitAtMost(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) return std::nullopt;
      std::this_thread::sleep_for(10ms);
    }
    waited_ = true;
    return status;
  }
  // The wait status (waitpid's).
  int wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    waited_ = true;
    return status;
  }
  std::string errors() const {
    std::ifstream in(errors_);
    return {std::istreambuf_iterator<char>(in), {}};
  }

 private:
  fs::path errors_;
  pid_t pid_ = -1;
  bool waited_ = false;
};

class SignalsCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    std::ofstream(dir_ / "scene.json")
        << R"({"coin": {"radius": 0.0375, "mass": 0.4}, "initial": {"theta": 10, "omega_Z": 12}, "duration": 60,
              "render": {"width": 64, "height": 48}})";
    std::ofstream(dir_ / "f_000.png") << kEarlierFrame;
  }

  // Hidden files in the directory: temporaries left, or named ones of a run under way.
  int hiddenFiles() const {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir_)) count += entry.path().filename().string()[0] == '.';
    return count;
  }

  // Waits (at most 10 s) until `run` writes at least `count` temporaries in `directory` (unnamed
  // ones are seen among its descriptors): its work is under way. The count seen is the answer:
  // counted again, a descriptor closing between the listing of /proc/PID/fd and its readlink could
  // make it one short (a sanitizer CI run failed so).
  static bool waitForTemporaries(const BackgroundRun& run, int count, const fs::path& directory) {
    for (int i = 0; i < 1000; ++i) {
      if (coinroll::testing::temporariesBeingWritten(run.pid(), directory) >= count) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }
  bool waitForTemporaries(const BackgroundRun& run, int count) const { return waitForTemporaries(run, count, dir_); }

  // Waits (at most 10 s) until a hidden temporary of `output` is in the directory.
  bool waitForHiddenFile(const std::string& output) const {
    const auto present = [&] {
      for (const auto& entry : fs::directory_iterator(dir_)) {
        if (entry.path().filename().string().rfind("." + output + ".partial-", 0) == 0) return true;
      }
      return false;
    };
    for (int i = 0; i < 1000 && !present(); ++i) std::this_thread::sleep_for(10ms);
    return present();
  }

  // The directory holds what the test put there, as it was: the scene and the earlier frame.
  void expectUntouched(const std::string& context) const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"f_000.png", "scene.json"})) << context;
    std::ifstream in(dir_ / "f_000.png");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), kEarlierFrame) << context;
  }
};

const std::vector<std::string> kSequence = {"render", "scene.json", "-q", "-o", "f_%03d.png"};

TEST_F(SignalsCliTest, EveryRequestToStopLeavesNoFile) {
  for (const int signal : {SIGHUP, SIGQUIT, SIGUSR1, SIGXCPU}) {
    const std::string name = sigabbrev_np(signal);
    BackgroundRun run(dir_, kSequence);
    ASSERT_TRUE(run.started());
    ASSERT_TRUE(waitForTemporaries(run, 5)) << "SIG" << name << ": the render never started staging frames";
    run.send(signal);
    const int status = run.wait();
    ASSERT_TRUE(WIFEXITED(status)) << "SIG" << name << " killed the run instead of stopping it";
    EXPECT_EQ(WEXITSTATUS(status), 1) << name;
    EXPECT_NE(run.errors().find("interrupted by SIG" + name), std::string::npos) << run.errors();
    expectUntouched("SIG" + name);
  }
}

// SIGSTOP holds the process while both signals arrive, so the second is there before the loop
// can answer the first: the deterministic way to the second signal's path, with frames staged
// (each run of a PNG sequence had left 706 and 848 of them) or an MP4 half encoded.
TEST_F(SignalsCliTest, ASecondSignalWhileFramesAreStagedEndsAtOnceAndLeavesNothing) {
  for (const std::string output : {"f_%03d.png", "o.mp4"}) {
    BackgroundRun run(dir_, {"render", "scene.json", "-q", "-o", output});
    ASSERT_TRUE(run.started());
    ASSERT_TRUE(waitForTemporaries(run, output == "o.mp4" ? 1 : 20)) << output << ": the render never started writing";
    run.send(SIGSTOP);
    run.send(SIGINT);
    run.send(SIGTERM);
    run.send(SIGCONT);
    const int status = run.wait();
    ASSERT_TRUE(WIFEXITED(status)) << output << ": killed by a signal";
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_NE(run.errors().find("stopped at once; no unfinished file is left"), std::string::npos) << run.errors();
    expectUntouched(output);
  }
}

// Opening a FIFO waits for a reader, in a call no loop can poll: the grace timer ends the run.
TEST_F(SignalsCliTest, ARequestToStopNotAnsweredInTimeEndsTheRunAtOnce) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  BackgroundRun run(dir_, {"simulate", "scene.json", "--csv", "fifo"});
  ASSERT_TRUE(run.started());
  ASSERT_TRUE(run.reachesKernelWait("wait_for_partner", 30s)) << "the run never blocked opening the FIFO";
  const auto sent = std::chrono::steady_clock::now();
  run.send(SIGTERM);
  const int status = run.wait();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_NE(run.errors().find("interrupted by SIGTERM and not stopped within 3 s"), std::string::npos) << run.errors();
  EXPECT_GT(seconds, 2.5);  // the grace was given
  EXPECT_LT(seconds, 4.5);  // and not more
}

// A sidecar is an output like the others: a request to stop leaves the earlier video and sidecar
// (or CSV and provenance) as they were and no temporary, and the run ends within the grace, with
// exit 1 (a render with --frame-times hung; simulate --provenance exited 0 and lost its provenance).
TEST_F(SignalsCliTest, ARequestToStopLeavesTheEarlierOutputsAndTheirSidecars) {
  const std::string earlier = "an earlier output, which must survive";
  for (const auto& [arguments, outputs] :
       {std::pair{std::vector<std::string>{"render", "scene.json", "-q", "-o", "o.mp4", "--frame-times", "t.csv"},
                  std::vector<std::string>{"o.mp4", "t.csv"}},
        std::pair{std::vector<std::string>{"simulate", "scene.json", "--csv", "o.csv", "--sample-dt", "0.001", "--set",
                                           "duration=1e4", "--provenance", "p.json"},
                  std::vector<std::string>{"o.csv", "p.json"}}}) {
    for (const std::string& name : outputs) std::ofstream(dir_ / name) << earlier;
    BackgroundRun run(dir_, arguments);
    ASSERT_TRUE(run.started());
    ASSERT_TRUE(waitForTemporaries(run, 1)) << arguments[0] << ": the run never started writing";
    std::this_thread::sleep_for(300ms);
    run.send(SIGINT);
    const std::optional<int> status = run.waitAtMost(10s);
    ASSERT_TRUE(status) << arguments[0] << ": still running 10 s after SIGINT";
    ASSERT_TRUE(WIFEXITED(*status)) << arguments[0] << ": killed by a signal";
    EXPECT_EQ(WEXITSTATUS(*status), 1) << arguments[0] << ": " << run.errors();
    EXPECT_NE(run.errors().find("interrupted by SIGINT; nothing was written to o."), std::string::npos) << run.errors();
    EXPECT_EQ(hiddenFiles(), 0) << arguments[0];
    for (const std::string& name : outputs) {
      std::ifstream in(dir_ / name);
      EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), earlier) << arguments[0] << ": " << name;
      fs::remove(dir_ / name);
    }
    expectUntouched(arguments[0]);
  }
}

// SIGKILL cannot be caught, so no handler removes anything: an unnamed temporary is freed by the
// kernel with the process (docs/outputs.md "Temporaries have no name while they are written"; each
// killed run used to leave its `.o.mp4.partial-PID-0`, and a PNG sequence every frame it had staged).
TEST_F(SignalsCliTest, SigkillMidWriteLeavesNoFile) {
  for (const auto& [arguments, output] :
       {std::pair{std::vector<std::string>{"render", "scene.json", "-q", "-o", "o.mp4"}, std::string("o.mp4")},
        std::pair{kSequence, std::string("f_%03d.png")},
        std::pair{std::vector<std::string>{"simulate", "scene.json", "--csv", "o.csv", "--sample-dt", "0.001", "--set",
                                           "duration=1e4"},
                  std::string("o.csv")}}) {
    BackgroundRun run(dir_, arguments);
    ASSERT_TRUE(run.started());
    ASSERT_TRUE(waitForTemporaries(run, output == "f_%03d.png" ? 20 : 1)) << output << ": the run never started";
    std::this_thread::sleep_for(200ms);  // well into the content
    run.send(SIGKILL);
    const int status = run.wait();
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << output << ": ended before the kill";
    expectUntouched(output);
  }
}

// Today's named temporaries, where O_TMPFILE is refused (forced here): a request to stop still
// leaves nothing, and SIGKILL leaves the one temporary, as the docs say it does there.
TEST_F(SignalsCliTest, NamedTemporariesStillGoOnARequestToStopButNotOnSigkill) {
  const coinroll::testing::NamedTemporaries named;
  const std::vector<std::string> arguments = {"render", "scene.json", "-q", "-o", "o.mp4"};
  {
    BackgroundRun run(dir_, arguments);
    ASSERT_TRUE(run.started());
    ASSERT_TRUE(waitForHiddenFile("o.mp4")) << "the render never made its named temporary";
    run.send(SIGTERM);
    const int status = run.wait();
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1) << run.errors();
    expectUntouched("SIGTERM");
  }
  BackgroundRun run(dir_, arguments);
  ASSERT_TRUE(run.started());
  ASSERT_TRUE(waitForHiddenFile("o.mp4")) << "the render never made its named temporary";
  run.send(SIGKILL);
  run.wait();
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    if (entry.path().filename().string()[0] == '.') left.push_back(entry.path().filename().string());
  }
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].rfind(".o.mp4.partial-" + std::to_string(run.pid()) + "-", 0), 0u) << left[0];
}

// The MP4 muxer reopens its file by name to move the index to the front (faststart). With the
// folder renamed under it, the named temporary's path led nowhere: FFmpeg printed its own
// "[mp4 @ 0x...] Unable to re-open" line and the temporary stayed in the renamed folder. An
// unnamed temporary is reopened through /proc/self/fd, so the video is finished; it is then not
// published into the renamed folder, which the user did not name, but refused with the reason.
TEST_F(SignalsCliTest, AnOutputFolderRenamedDuringARenderIsAClearErrorAndLeavesNothing) {
  fs::create_directory(dir_ / "out");
  BackgroundRun run(dir_, {"render", "scene.json", "-q", "-o", "out/x.mp4", "--set", "duration=20"});
  ASSERT_TRUE(run.started());
  ASSERT_TRUE(waitForTemporaries(run, 1, dir_ / "out")) << "the render never started writing";
  std::this_thread::sleep_for(300ms);  // past the muxer's first open: the faststart reopen is the one to survive
  fs::rename(dir_ / "out", dir_ / "renamed");
  const std::optional<int> status = run.waitAtMost(60s);
  ASSERT_TRUE(status) << "still running 60 s later";
  ASSERT_TRUE(WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 1) << run.errors();
  const std::string errors = run.errors();
  EXPECT_NE(errors.find("out/x.mp4: cannot move the finished MP4 into place: No such file or directory: its "
                        "directory " +
                        fs::canonical(dir_).string() +
                        "/out was renamed or removed while it was "
                        "written"),
            std::string::npos)
      << errors;
  EXPECT_EQ(errors.find("Unable to re-open"), std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_TRUE(fs::is_empty(dir_ / "renamed")) << "neither the video nor a temporary";
}

}  // namespace
