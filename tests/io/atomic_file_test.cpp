// The output layer (src/io: OutputFile, OutputGroup, resolveDestination): atomic files, links
// written through, streams written directly, modes kept, groups all or nothing.
// (One file for all of src/io: tests/CMakeLists.txt builds io_test from this source.)

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>

#include "io/destination.h"
#include "io/output_file.h"
#include "io/output_group.h"
#include "scratch_dir.h"
#include "temporaries.h"

namespace fs = std::filesystem;
using coinroll::io::Destination;
using coinroll::io::OutputFile;
using coinroll::io::OutputGroup;
using coinroll::testing::NamedTemporaries;
using coinroll::testing::ScratchDirectory;

namespace {

// The user nobody, for what root is not refused.
constexpr uid_t kNobody = 65534;

std::string contentOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const fs::path& path, const std::string& content) { std::ofstream(path, std::ios::binary) << content; }

mode_t modeOf(const fs::path& path) {
  struct stat info {};
  EXPECT_EQ(::lstat(path.c_str(), &info), 0) << path;
  return info.st_mode & 07777;
}

// The directory a temporary is in: an unnamed one's /proc/self/fd link reads "DIRECTORY/#INODE (deleted)".
fs::path directoryOf(const fs::path& temporary) {
  return temporary.parent_path() == "/proc/self/fd" ? fs::read_symlink(temporary).parent_path()
                                                    : temporary.parent_path();
}

// The message of the std::exception `action` throws, or "" when it throws none.
template <class Action>
std::string errorOf(Action action) {
  try {
    action();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// A pipe whose ends close with the test.
struct Pipe {
  int read = -1, write = -1;
  Pipe() {
    int ends[2];
    EXPECT_EQ(::pipe(ends), 0);
    read = ends[0];
    write = ends[1];
  }
  ~Pipe() {
    if (read >= 0) ::close(read);
    if (write >= 0) ::close(write);
  }
  std::string drain() {
    ::close(write);
    write = -1;
    std::string bytes;
    char chunk[4096];
    for (ssize_t n; (n = ::read(read, chunk, sizeof chunk)) > 0;) bytes.append(chunk, static_cast<std::size_t>(n));
    return bytes;
  }
};

// Sets the umask for one test (the mode tests must not depend on the caller's).
struct Umask {
  mode_t previous;
  explicit Umask(mode_t mask) : previous(::umask(mask)) {}
  ~Umask() { ::umask(previous); }
};

}  // namespace

// --- regular files: atomic replacement

TEST(OutputFile, NothingAppearsUnderTheFinalNameUntilCommit) {
  const ScratchDirectory scratch;
  const fs::path target = scratch / "out.csv";
  {
    OutputFile file(target, "CSV");
    file.stream() << "data\n";
    file.stream().flush();
    EXPECT_FALSE(fs::exists(target));
    file.commit();
  }
  EXPECT_EQ(contentOf(target), "data\n");
  EXPECT_EQ(scratch.fileCount(), 1);
}

TEST(OutputFile, AbandonedFileLeavesNothingBehind) {
  const ScratchDirectory scratch;
  {
    OutputFile file(scratch / "out.csv", "CSV");
    file.write("half");
  }
  EXPECT_TRUE(fs::is_empty(scratch.path()));
}

// Unnamed (O_TMPFILE), so a process killed while it writes leaves nothing (docs/outputs.md "Temporaries
// have no name while they are written"): the scratch directory (in /tmp, a file system that has it)
// shows no file until the commit.
TEST(OutputFile, TheTemporaryHasNoNameUntilCommit) {
  const ScratchDirectory scratch;
  OutputFile file(scratch / "out.csv", "CSV");
  file.write("data\n");
  EXPECT_EQ(scratch.fileCount(), 0);
  EXPECT_EQ(file.temporaryPath().parent_path(), "/proc/self/fd");
  file.commit();
  EXPECT_EQ(contentOf(scratch / "out.csv"), "data\n");
  EXPECT_EQ(scratch.fileCount(), 1);
}

// Where O_TMPFILE is refused (forced here): the hidden name beside the output, as before.
TEST(OutputFile, WithoutUnnamedFilesTheTemporaryIsAHiddenNameBesideTheOutput) {
  const NamedTemporaries named;
  const ScratchDirectory scratch;
  {
    OutputFile file(scratch / "out.csv", "CSV");
    file.write("data\n");
    const std::string name = file.temporaryPath().filename().string();
    EXPECT_EQ(file.temporaryPath().parent_path(), fs::canonical(scratch.path()));
    EXPECT_EQ(name.rfind(".out.csv.partial-" + std::to_string(::getpid()) + "-", 0), 0u) << name;
    EXPECT_EQ(contentOf(file.temporaryPath()), "data\n");
    file.commit();
  }
  EXPECT_EQ(contentOf(scratch / "out.csv"), "data\n");
  EXPECT_EQ(scratch.fileCount(), 1);
  {
    OutputFile abandoned(scratch / "other.csv", "CSV");
    abandoned.write("half");
    EXPECT_EQ(scratch.fileCount(), 2);
  }
  EXPECT_EQ(scratch.fileCount(), 1);
}

// A library that writes by path (the MP4 muxer, and its faststart pass that reopens the file) is
// given /proc/self/fd/N, which reaches the file even after its folder is renamed; the output is
// then not published into a folder the user did not name, and the error says why.
TEST(OutputFile, AFolderRenamedDuringTheWriteIsAClearErrorAndLeavesNothing) {
  const ScratchDirectory scratch;
  fs::create_directory(scratch / "out");
  OutputFile file(scratch / "out" / "x.mp4", "MP4", OutputFile::Access::ByPath);
  fs::rename(scratch / "out", scratch / "renamed");
  std::ofstream written(file.temporaryPath(), std::ios::binary);
  written << "encoded bytes";
  written.close();
  EXPECT_FALSE(written.fail()) << "the temporary cannot be reopened by its path";
  EXPECT_EQ(contentOf(file.temporaryPath()), "encoded bytes");
  const std::string error = errorOf([&] { file.commit(); });
  EXPECT_EQ(error, (scratch / "out" / "x.mp4").string() +
                       ": cannot move the finished output into place: No such file or directory: its directory " +
                       (fs::canonical(scratch.path()) / "out").string() +
                       " was renamed or removed while it was written");
  EXPECT_TRUE(fs::is_empty(scratch / "renamed"));
}

TEST(OutputFile, MissingDirectoryIsReportedWithThePath) {
  const ScratchDirectory scratch;
  const std::string error = errorOf([&] { OutputFile file(scratch / "no_such_dir" / "x" / "out.csv", "CSV"); });
  EXPECT_NE(error.find("out.csv: cannot write: directory '"), std::string::npos) << error;
  EXPECT_NE(error.find("' does not exist"), std::string::npos) << error;
}

TEST(OutputFile, ADirectoryOnTheWayThatIsAFileIsCalledThat) {
  const ScratchDirectory scratch;
  writeFile(scratch / "plain", "x");
  const std::string error = errorOf([&] { OutputFile file(scratch / "plain" / "out.csv", "CSV"); });
  EXPECT_NE(error.find("plain' is not a directory"), std::string::npos) << error;
}

TEST(OutputFile, ANameTheFileSystemCannotHoldIsRefusedBeforeAnyWork) {
  // Refused when the output is opened, not at the rename after all the frames or rows.
  const ScratchDirectory scratch;
  const long limit = ::pathconf(scratch.path().c_str(), _PC_NAME_MAX);
  ASSERT_GT(limit, 4);
  const std::string longest = std::string(static_cast<std::size_t>(limit) - 4, 'a') + ".csv";
  {
    OutputFile file(scratch / longest, "CSV");
    file.write("data\n");
    file.commit();
  }
  EXPECT_TRUE(fs::exists(scratch / longest));
  fs::remove(scratch / longest);
  const std::string error = errorOf([&] { OutputFile file(scratch / ("a" + longest), "CSV"); });
  EXPECT_NE(error.find("File name too long"), std::string::npos) << error;
  EXPECT_TRUE(fs::is_empty(scratch.path()));
}

TEST(OutputFile, AnEmptyNameOrADirectoryNameIsRefused) {
  const ScratchDirectory scratch;
  EXPECT_THROW(OutputFile("", "CSV"), std::invalid_argument);
  fs::create_directory(scratch / "sub");
  EXPECT_NE(errorOf([&] { OutputFile file(scratch / "sub", "CSV"); }).find("is a directory"), std::string::npos);
  EXPECT_NE(errorOf([&] { OutputFile file(scratch.path().string() + "/sub/", "CSV"); }).find("names a directory"),
            std::string::npos);
  EXPECT_EQ(scratch.fileCount(), 1);
}

TEST(OutputFile, AFailedWriteNamesTheOutputAndTheReason) {
  const ScratchDirectory scratch;
  OutputFile file("/dev/full", "CSV");
  const std::string error = errorOf([&] {
    for (int row = 0; row < 100000; ++row) file.stream() << "0.1,0.2,0.3\n";
    file.commit();
  });
  EXPECT_EQ(error, "/dev/full: writing the CSV failed: No space left on device");
}

// --- modes and permissions

TEST(OutputFile, AReplacedFileKeepsItsMode) {
  const ScratchDirectory scratch;
  const Umask umask(022);
  const fs::path target = scratch / "secret.csv";
  writeFile(target, "old\n");
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);  // 0600
  OutputFile file(target, "CSV");
  struct stat temporary {};
  ASSERT_EQ(::stat(file.temporaryPath().c_str(), &temporary), 0);
  EXPECT_EQ(temporary.st_mode & 07777, 0600u) << "the temporary is private before any content";
  file.write("new\n");
  file.commit();
  EXPECT_EQ(contentOf(target), "new\n");
  EXPECT_EQ(modeOf(target), 0600u);
}

TEST(OutputFile, ANewFileGetsTheUmasksMode) {
  const ScratchDirectory scratch;
  const Umask umask(027);
  OutputFile file(scratch / "new.csv", "CSV");
  file.commit();
  EXPECT_EQ(modeOf(scratch / "new.csv"), 0640u);
}

TEST(OutputFile, AFileTheUserCouldNotWriteIsRefusedAndKept) {
  const ScratchDirectory scratch;
  const fs::path target = scratch / "locked.csv";
  writeFile(target, "keep\n");
  fs::permissions(target, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);  // 0444
  if (::geteuid() != 0) {
    const std::string error = errorOf([&] { OutputFile file(target, "CSV"); });
    EXPECT_NE(error.find("locked.csv: cannot write: Permission denied: the file is not writable for you"),
              std::string::npos)
        << error;
  } else {
    // Root may write anything, so the refusal is checked as nobody, in a directory nobody may
    // write (where the rename would have replaced root's read-only file).
    fs::permissions(scratch.path(), fs::perms::all);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (::setgid(kNobody) != 0 || ::setuid(kNobody) != 0) ::_exit(3);
      const std::string error = errorOf([&] { OutputFile file(target, "CSV"); });
      ::_exit(error.find("the file is not writable for you") != std::string::npos ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "nobody replaced root's read-only file";
  }
  EXPECT_EQ(contentOf(target), "keep\n");
  EXPECT_EQ(scratch.fileCount(), 1);
}

TEST(OutputFile, AnotherUsersFileInAStickyDirectoryIsRefusedUpFront) {
  // Writable for everyone, so only the sticky bit stops the rename, and only at the end.
  if (::geteuid() != 0) GTEST_SKIP() << "needs a file of another user: run as root";
  const ScratchDirectory scratch;
  const fs::path target = scratch / "shared.csv";
  writeFile(target, "root's\n");
  fs::permissions(target, fs::perms::all & ~fs::perms::owner_exec & ~fs::perms::group_exec & ~fs::perms::others_exec);
  fs::permissions(scratch.path(), fs::perms::all | fs::perms::sticky_bit);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::setgid(kNobody) != 0 || ::setuid(kNobody) != 0) ::_exit(3);
    const std::string error = errorOf([&] { OutputFile file(target, "CSV"); });
    ::_exit(error.find("it belongs to another user in the sticky directory") != std::string::npos ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(scratch.fileCount(), 1);
}

TEST(OutputFile, AsRootAReplacedFileKeepsItsOwner) {
  if (::geteuid() != 0) GTEST_SKIP() << "only root can give a file to another user";
  const ScratchDirectory scratch;
  const fs::path target = scratch / "theirs.csv";
  writeFile(target, "old\n");
  ASSERT_EQ(::chown(target.c_str(), kNobody, kNobody), 0);
  OutputFile file(target, "CSV");
  file.write("new\n");
  file.commit();
  struct stat info {};
  ASSERT_EQ(::stat(target.c_str(), &info), 0);
  EXPECT_EQ(info.st_uid, kNobody);
  EXPECT_EQ(info.st_gid, kNobody);
}

// --- symbolic links

TEST(OutputFile, ALinkIsWrittenThroughToItsTargetAndStaysALink) {
  const ScratchDirectory scratch;
  fs::create_directory(scratch / "data");
  writeFile(scratch / "data" / "target.csv", "old\n");
  fs::create_symlink("data/target.csv", scratch / "link.csv");
  {
    OutputFile file(scratch / "link.csv", "CSV");
    EXPECT_EQ(directoryOf(file.temporaryPath()), fs::canonical(scratch / "data")) << "beside the target";
    file.write("new\n");
    file.commit();
  }
  EXPECT_TRUE(fs::is_symlink(scratch / "link.csv"));
  EXPECT_EQ(fs::read_symlink(scratch / "link.csv"), "data/target.csv");
  EXPECT_EQ(contentOf(scratch / "data" / "target.csv"), "new\n");
  EXPECT_EQ(scratch.fileCount(), 2);
  EXPECT_EQ(std::distance(fs::directory_iterator(scratch / "data"), fs::directory_iterator{}), 1);
}

TEST(OutputFile, AChainOfLinksAndADanglingLinkAreFollowed) {
  const ScratchDirectory scratch;
  fs::create_symlink("middle.csv", scratch / "first.csv");
  fs::create_symlink(scratch / "new.csv", scratch / "middle.csv");  // absolute, and its target does not exist
  OutputFile file(scratch / "first.csv", "CSV");
  file.write("made\n");
  file.commit();
  EXPECT_EQ(contentOf(scratch / "new.csv"), "made\n");
  EXPECT_TRUE(fs::is_symlink(scratch / "first.csv"));
  EXPECT_TRUE(fs::is_symlink(scratch / "middle.csv"));
}

TEST(OutputFile, ALinkLoopIsRefusedNamingTheOutput) {
  const ScratchDirectory scratch;
  fs::create_symlink("b.csv", scratch / "a.csv");
  fs::create_symlink("a.csv", scratch / "b.csv");
  const std::string error = errorOf([&] { OutputFile file(scratch / "a.csv", "CSV"); });
  EXPECT_NE(error.find("a.csv: cannot write: Too many levels of symbolic links"), std::string::npos) << error;
  EXPECT_EQ(scratch.fileCount(), 2);
}

// --- streams: devices, FIFOs, descriptors

TEST(Destination, DescriptorNamesAreDescriptorsNotTheFilesBehindThem) {
  // As root, renaming onto /dev/stdout once replaced the system's link with a file.
  const Pipe pipe;
  for (const auto& [name, descriptor] :
       std::vector<std::pair<std::string, int>>{{"/dev/stdout", 1},
                                                {"/dev/stderr", 2},
                                                {"/dev/fd/" + std::to_string(pipe.write), pipe.write},
                                                {"/proc/self/fd/" + std::to_string(pipe.write), pipe.write}}) {
    const Destination destination = coinroll::io::resolveDestination(name);
    EXPECT_EQ(destination.kind, Destination::Kind::Descriptor) << name;
    EXPECT_EQ(destination.descriptor, descriptor) << name;
  }
  EXPECT_EQ(coinroll::io::resolveDestination("/dev/null").kind, Destination::Kind::Device);
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
}

TEST(OutputFile, APipeUnderDevFdIsWrittenDirectly) {
  // What `--csv >(gzip > t.csv.gz)` passes.
  const ScratchDirectory scratch;
  Pipe pipe;
  {
    OutputFile file("/dev/fd/" + std::to_string(pipe.write), "CSV");
    EXPECT_TRUE(file.temporaryPath().empty());
    file.stream() << "t,theta\n" << 0.5 << ",1\n";
    file.commit();
  }
  EXPECT_EQ(pipe.drain(), "t,theta\n0.5,1\n");
}

TEST(OutputFile, AFifoIsStreamedToAndStaysAFifo) {
  const ScratchDirectory scratch;
  const fs::path fifo = scratch / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = contentOf(fifo); });
  {
    OutputFile file(fifo, "CSV");
    file.write("through the fifo\n");
    file.commit();
  }
  reader.join();
  EXPECT_EQ(received, "through the fifo\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(scratch.fileCount(), 1);
}

TEST(OutputFile, DevNullTakesTheOutputAndStaysADevice) {
  OutputFile file("/dev/null", "CSV");
  file.write("discarded\n");
  file.commit();
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputFile, ASeekableOutputForAPipeIsMadeInTmpdirAndCopiedAtCommit) {
  // The MP4 muxer's faststart rereads its file; a pipe cannot be reread.
  Pipe pipe;
  fs::path temporary;
  {
    OutputFile file("/dev/fd/" + std::to_string(pipe.write), "MP4", OutputFile::Access::ByPath);
    temporary = file.temporaryPath();
    EXPECT_EQ(directoryOf(temporary), fs::temp_directory_path());
    std::ofstream(temporary, std::ios::binary) << "encoded bytes";
    file.commit();
  }
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(pipe.drain(), "encoded bytes");
}

TEST(OutputFile, AReaderThatLeftIsABrokenPipe) {
  Pipe pipe;
  ::close(pipe.read);
  pipe.read = -1;
  const auto previous = std::signal(SIGPIPE, SIG_IGN);  // as a shell's `trap '' PIPE`
  const std::string error = errorOf([&] {
    OutputFile file("/dev/fd/" + std::to_string(pipe.write), "CSV");
    file.write("nobody reads this\n");
  });
  std::signal(SIGPIPE, previous);
  EXPECT_EQ(error, "/dev/fd/" + std::to_string(pipe.write) + ": writing the CSV failed: Broken pipe");
}

TEST(OutputFile, ADescriptorThatCannotBeWrittenIsRefused) {
  const Pipe pipe;
  EXPECT_NE(
      errorOf([&] { OutputFile file("/dev/fd/" + std::to_string(pipe.read), "CSV"); }).find("is open for reading only"),
      std::string::npos);
  EXPECT_NE(errorOf([&] { OutputFile file("/dev/fd/987654", "CSV"); }).find("descriptor 987654 is not open"),
            std::string::npos);
}

// --- groups: all or nothing

TEST(OutputGroup, AFailedRenameRollsBackSoTheEarlierFilesStay) {
  const NamedTemporaries named;  // a name the test can remove, so that its rename fails
  const ScratchDirectory scratch;
  for (int i = 0; i < 3; ++i) writeFile(scratch / ("f_" + std::to_string(i)), "old " + std::to_string(i));
  writeFile(scratch / "f_3", "old stale 3");
  {
    OutputGroup group("PNG");
    std::vector<fs::path> temporaries;
    for (int i = 0; i < 3; ++i) {
      temporaries.push_back(group.add(scratch / ("f_" + std::to_string(i))));
      writeFile(temporaries.back(), "new " + std::to_string(i));
    }
    group.retire(scratch / "f_3");
    fs::remove(temporaries[2]);  // the last rename fails, after two have been done
    const std::string error = errorOf([&] { group.commit(); });
    EXPECT_NE(error.find("f_2: cannot move the finished PNG into place: No such file or directory; nothing was "
                         "published and the earlier files are as they were"),
              std::string::npos)
        << error;
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(contentOf(scratch / ("f_" + std::to_string(i))), "old " + std::to_string(i));
  EXPECT_EQ(contentOf(scratch / "f_3"), "old stale 3");
  EXPECT_EQ(scratch.fileCount(), 4) << "no temporary and no kept copy is left";
}

// Each unnamed temporary of a group holds a descriptor until the commit; past a quarter of the
// limit on open files the rest are named, so a long PNG sequence never runs out of descriptors.
TEST(OutputGroup, PastItsShareOfOpenFilesAGroupNamesItsTemporaries) {
  const ScratchDirectory scratch;
  rlimit limit{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &limit), 0);
  const rlimit small{64, limit.rlim_max};
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &small), 0);
  {
    OutputGroup group("PNG");
    for (int i = 0; i < 20; ++i) writeFile(group.add(scratch / ("f_" + std::to_string(i))), std::to_string(i));
    EXPECT_EQ(scratch.fileCount(), 4) << "16 unnamed, then named ones";
    group.commit();
  }
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &limit), 0);
  EXPECT_EQ(scratch.fileCount(), 20);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(contentOf(scratch / ("f_" + std::to_string(i))), std::to_string(i));
}

TEST(OutputGroup, ACommitPublishesEveryFileAndRemovesTheRetiredOnes) {
  const ScratchDirectory scratch;
  const Umask umask(022);
  writeFile(scratch / "f_0", "old 0");
  fs::permissions(scratch / "f_0", fs::perms::owner_read | fs::perms::owner_write);
  writeFile(scratch / "f_5", "stale");
  writeFile(scratch / "other", "not ours");
  {
    OutputGroup group("PNG");
    writeFile(group.add(scratch / "f_0"), "new 0");
    writeFile(group.add(scratch / "f_1"), "new 1");
    group.retire(scratch / "f_5");
    group.retire(scratch / "already_gone");  // removed by someone else meanwhile: not an error
    EXPECT_EQ(contentOf(scratch / "f_0"), "old 0") << "nothing changes before the commit";
    group.commit();
  }
  EXPECT_EQ(contentOf(scratch / "f_0"), "new 0");
  EXPECT_EQ(modeOf(scratch / "f_0"), 0600u);
  EXPECT_EQ(contentOf(scratch / "f_1"), "new 1");
  EXPECT_FALSE(fs::exists(scratch / "f_5"));
  EXPECT_EQ(contentOf(scratch / "other"), "not ours");
  EXPECT_EQ(scratch.fileCount(), 3);
}

TEST(OutputGroup, AnUncommittedGroupLeavesTheDirectoryAsItWas) {
  const ScratchDirectory scratch;
  writeFile(scratch / "f_0", "old");
  {
    OutputGroup group("PNG");
    writeFile(group.add(scratch / "f_0"), "new");
    writeFile(group.add(scratch / "f_1"), "new");
    group.retire(scratch / "f_0");
  }
  EXPECT_EQ(contentOf(scratch / "f_0"), "old");
  EXPECT_EQ(scratch.fileCount(), 1);
}

// A video and its sidecar: OutputFiles of one group are published by the group's commit(), all or
// none, and two of them leading to one file are refused whatever the spelling.
TEST(OutputGroup, OutputFilesOfAGroupArePublishedByItsCommitOnly) {
  const ScratchDirectory scratch;
  writeFile(scratch / "v.mp4", "old video");
  writeFile(scratch / "t.csv", "old sidecar");
  {
    OutputGroup group;
    OutputFile video(scratch / "v.mp4", "MP4", OutputFile::Access::ByPath, &group);
    OutputFile sidecar(scratch / "t.csv", "frame times CSV", OutputFile::Access::Sequential, &group);
    const std::string error =
        errorOf([&] { OutputFile again(scratch / "." / "v.mp4", "CSV", OutputFile::Access::Sequential, &group); });
    EXPECT_NE(error.find("cannot write: it leads to the same file as " + (scratch / "v.mp4").string() +
                         " (through a link, or as another name of that file); the MP4 and the CSV each need a file of "
                         "their own"),
              std::string::npos)
        << error;
    writeFile(video.temporaryPath(), "new video");
    sidecar.write("new sidecar");
    video.commit();
    sidecar.commit();
    EXPECT_EQ(contentOf(scratch / "v.mp4"), "old video") << "an OutputFile of a group does not publish itself";
    EXPECT_EQ(contentOf(scratch / "t.csv"), "old sidecar");
  }  // never committed: both earlier files stay
  EXPECT_EQ(contentOf(scratch / "v.mp4"), "old video");
  EXPECT_EQ(contentOf(scratch / "t.csv"), "old sidecar");
  EXPECT_EQ(scratch.fileCount(), 2) << "no temporary is left";
  {
    OutputGroup group;
    OutputFile video(scratch / "v.mp4", "MP4", OutputFile::Access::ByPath, &group);
    OutputFile sidecar(scratch / "t.csv", "frame times CSV", OutputFile::Access::Sequential, &group);
    writeFile(video.temporaryPath(), "new video");
    sidecar.write("new sidecar");
    video.commit();
    sidecar.commit();
    group.commit();
  }
  EXPECT_EQ(contentOf(scratch / "v.mp4"), "new video");
  EXPECT_EQ(contentOf(scratch / "t.csv"), "new sidecar");
  EXPECT_EQ(scratch.fileCount(), 2);
}

TEST(OutputGroup, AFileOfTheGroupMayBeALinkButNotAStream) {
  const ScratchDirectory scratch;
  writeFile(scratch / "target", "old");
  fs::create_symlink("target", scratch / "f_0");
  {
    OutputGroup group("PNG");
    writeFile(group.add(scratch / "f_0"), "new");
    EXPECT_NE(errorOf([&] { group.add("/dev/null"); }).find("each PNG of a sequence is a file of its own"),
              std::string::npos);
    group.commit();
  }
  EXPECT_TRUE(fs::is_symlink(scratch / "f_0"));
  EXPECT_EQ(contentOf(scratch / "target"), "new");
  EXPECT_EQ(scratch.fileCount(), 2);
}
