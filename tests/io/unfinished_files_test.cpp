// The list of unfinished files (io/unfinished_files.h): every temporary the output layer makes is
// on it until published or removed, and removing them, as a process ending at once does, leaves
// the directory as it was before the run.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/output_file.h"
#include "io/output_group.h"
#include "io/unfinished_files.h"
#include "scratch_dir.h"
#include "temporaries.h"

namespace fs = std::filesystem;
using coinroll::io::OutputFile;
using coinroll::io::OutputGroup;
using coinroll::io::unfinishedFileCount;
using coinroll::testing::ScratchDirectory;

namespace {

std::string contentOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const fs::path& path, const std::string& content) { std::ofstream(path, std::ios::binary) << content; }

std::atomic<bool> handled{false};
extern "C" void onSignal(int) { handled = true; }
extern "C" void removeAndEnd(int) {
  coinroll::io::removeUnfinishedFiles();
  ::_exit(0);
}

}  // namespace

// The list holds named temporaries (where O_TMPFILE is refused, forced here) and the names given at
// commit; an unnamed temporary has no name to remove, so it is not listed while it is written.
TEST(UnfinishedFiles, ANamedTemporaryIsListedUntilItIsPublishedOrRemoved) {
  const ScratchDirectory scratch;
  const std::size_t before = unfinishedFileCount();
  {
    OutputFile file(scratch / "unnamed.csv", "CSV");
    OutputGroup group("PNG");
    writeFile(group.add(scratch / "f_0"), "new");
    EXPECT_EQ(unfinishedFileCount(), before) << "an unnamed temporary is listed";
  }
  const coinroll::testing::NamedTemporaries named;
  {
    OutputFile published(scratch / "a.csv", "CSV");
    OutputFile abandoned(scratch / "b.csv", "CSV");
    OutputFile scratchFile("/dev/null", "MP4", OutputFile::Access::ByPath);  // made in $TMPDIR
    EXPECT_EQ(unfinishedFileCount(), before + 3);
    published.commit();
    scratchFile.commit();
    EXPECT_EQ(unfinishedFileCount(), before + 1);
  }
  EXPECT_EQ(unfinishedFileCount(), before);

  writeFile(scratch / "f_0", "old");
  writeFile(scratch / "f_9", "stale");
  OutputGroup group("PNG");
  for (const char* name : {"f_0", "f_1", "f_2"}) writeFile(group.add(scratch / name), "new");
  group.retire(scratch / "f_9");
  EXPECT_EQ(unfinishedFileCount(), before + 3);
  group.commit();  // the kept copies of f_0 and f_9 are listed while it runs, and gone after
  EXPECT_EQ(unfinishedFileCount(), before);
  EXPECT_EQ(scratch.fileCount(), 4);
}

// What a second Ctrl-C does: a process with a half-written file and half a PNG sequence staged
// removes them and ends, without running a destructor; with named temporaries too.
TEST(UnfinishedFiles, RemovingThemLeavesTheDirectoryAsItWas) {
  for (const bool named : {false, true}) {
    const ScratchDirectory scratch;
    writeFile(scratch / "f_0", "earlier");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (named) ::setenv("COINROLL_NAMED_TEMPORARIES", "1", 1);
      OutputFile file(scratch / "out.csv", "CSV");
      file.write("half a CSV");
      OutputGroup group("PNG");
      for (const char* name : {"f_0", "f_1", "f_2"}) writeFile(group.add(scratch / name), "new frame");
      coinroll::io::removeUnfinishedFiles();
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(scratch.fileCount(), 1) << (named ? "named" : "unnamed");
    EXPECT_EQ(contentOf(scratch / "f_0"), "earlier");
  }
}

// A handler run after (or inside) a removal on the same thread removes again rather than wait for
// the lock its own thread keeps: SIGPIPE raised by the forced end's message to a dead stderr spun at
// 100 % CPU for ever (docs/signals_and_limits.md "The staging area a handler can remove").
TEST(UnfinishedFiles, ARemovalOnTheThreadThatRemovedDoesNotWaitForItself) {
  const ScratchDirectory scratch;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::alarm(10);  // a wait for itself ends by SIGALRM rather than hang the test
    struct sigaction action {};
    action.sa_handler = removeAndEnd;
    ::sigemptyset(&action.sa_mask);
    ::sigaction(SIGUSR1, &action, nullptr);
    OutputFile file(scratch / "out.csv", "CSV");
    file.write("half a CSV");
    coinroll::io::removeUnfinishedFiles();
    ::raise(SIGUSR1);
    ::_exit(1);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status) << " (SIGALRM: it waited for itself)";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(scratch.fileCount(), 0);
}

// A section holds signals off its thread, so a handler never runs with the list half changed on
// the thread that changes it; they arrive when it ends.
TEST(UnfinishedFiles, ASectionHoldsSignalsUntilItEnds) {
  struct sigaction action {
  }, previous{};
  action.sa_handler = onSignal;
  ::sigemptyset(&action.sa_mask);
  ASSERT_EQ(::sigaction(SIGUSR1, &action, &previous), 0);
  handled = false;
  {
    const coinroll::io::UnfinishedFilesSection section;
    ::raise(SIGUSR1);
    EXPECT_FALSE(handled);
  }
  EXPECT_TRUE(handled);
  ::sigaction(SIGUSR1, &previous, nullptr);
}
