// The pieces a batch service stands on: --out checks, containment, staged results, locks that
// die with their holder, and manifest lines.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <thread>

#include "io/atomic_file.h"
#include "io/file_lock.h"
#include "io/output_folder.h"
#include "io/staged_folder.h"
#include "simplify/manifest.h"
#include "error_message.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::io {
namespace {

namespace fs = std::filesystem;

std::string refusal(const fs::path& dir, const OutputFolderRule& rule) {
    return test::errorMessage([&] { checkOutputFolder(dir, rule); });
}

TEST(OutputFolder, RootFilesAndForeignFoldersAreRefused) {
    const auto dir = test::scratchDir("output_folder");
    EXPECT_NE(refusal("/", {}).find("filesystem root"), std::string::npos);
    EXPECT_NE(refusal(dir / ".." / ".." / ".." / ".." / ".." / ".." / ".." / ".." / "..", {}).find("filesystem root"),
              std::string::npos);
    std::ofstream(dir / "file") << "x";
    EXPECT_NE(refusal(dir / "file", {}).find("not a folder"), std::string::npos);
    EXPECT_NE(refusal(dir / "file" / "sub", {}).find("cannot be created"), std::string::npos);

    fs::create_directories(dir / "foreign");
    std::ofstream(dir / "foreign" / "notes.txt") << "x";
    EXPECT_NE(refusal(dir / "foreign", {}).find("--force"), std::string::npos);
    EXPECT_EQ(refusal(dir / "foreign", {.force = true}), "");
    EXPECT_EQ(refusal(dir / "foreign", {.ownMarkers = {"notes.txt"}}), "");  // a previous run's
    EXPECT_EQ(refusal(dir / "new" / "deeper", {}), "");
    fs::create_directories(dir / "empty");
    EXPECT_EQ(refusal(dir / "empty", {}), "");
}

TEST(OutputFolder, AReadOnlyParentIsRefused) {
    if (geteuid() == 0) GTEST_SKIP() << "root may write anywhere";
    const auto dir = test::scratchDir("output_folder_readonly");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    const std::string message = refusal(dir / "out", {});
    fs::permissions(dir, fs::perms::owner_all);
    EXPECT_NE(message.find("cannot be created in"), std::string::npos) << message;
}

TEST(OutputFolder, ContainmentIsLexicalAndStrict) {
    EXPECT_TRUE(isStrictlyInside("out/a", "out"));
    EXPECT_TRUE(isStrictlyInside("out/a/b", "out/"));
    EXPECT_FALSE(isStrictlyInside("out", "out"));
    EXPECT_FALSE(isStrictlyInside("out/..", "out"));
    EXPECT_FALSE(isStrictlyInside("out/.", "out"));
    EXPECT_FALSE(isStrictlyInside("out/a/../..", "out"));
    EXPECT_FALSE(isStrictlyInside("outside", "out"));
}

TEST(StagedFolder, ResultsAppearOnCommitAndVanishWithout) {
    const auto dir = test::scratchDir("staged_folder");
    fs::create_directories(dir / "out" / "baselines");
    std::ofstream(dir / "out" / "baselines" / "old.glb") << "old";
    std::ofstream(dir / "out" / "checkpoint.bin") << "kept";
    {
        StagedFolder staged(dir / "out");
        std::ofstream(staged.path() / "report.json") << "{}";
        fs::create_directories(staged.path() / "baselines");
        std::ofstream(staged.path() / "baselines" / "new.glb") << "new";
        EXPECT_FALSE(fs::exists(dir / "out" / "report.json"));
        staged.commit();
    }
    EXPECT_TRUE(fs::exists(dir / "out" / "report.json"));
    EXPECT_TRUE(fs::exists(dir / "out" / "baselines" / "new.glb"));
    EXPECT_FALSE(fs::exists(dir / "out" / "baselines" / "old.glb"));  // the folder is replaced whole
    EXPECT_TRUE(fs::exists(dir / "out" / "checkpoint.bin"));
    {
        StagedFolder failed(dir / "out");
        std::ofstream(failed.path() / "initial_cage.obj") << "half";
    }  // no commit: an exception, a stop request
    EXPECT_FALSE(fs::exists(dir / "out" / "initial_cage.obj"));
    for (const auto& entry : fs::directory_iterator(dir / "out"))
        EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
    const auto dir = test::scratchDir("atomic_file");
    writeTextAtomically(dir / "report.json", "old");
    EXPECT_THROW(writeAtomically(dir / "report.json",
                                 [](const fs::path& temporary) {
                                     std::ofstream(temporary) << "half";
                                     throw Error("the writer failed");
                                 }),
                 Error);
    std::ifstream in(dir / "report.json");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "old");
    for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "report.json");
}

TEST(AtomicFile, ConcurrentWritersNeverMixTheirBytes) {
    const auto dir = test::scratchDir("atomic_file_threads");
    std::vector<std::thread> writers;
    for (int t = 0; t < 8; ++t)
        writers.emplace_back([&, t] {
            for (int k = 0; k < 20; ++k) writeTextAtomically(dir / "out.bin", std::string(1 << 16, char('a' + t)));
        });
    for (auto& w : writers) w.join();
    std::ifstream in(dir / "out.bin", std::ios::binary);
    const std::string bytes(std::istreambuf_iterator<char>(in), {});
    ASSERT_EQ(bytes.size(), size_t(1) << 16);
    EXPECT_EQ(bytes.find_first_not_of(bytes[0]), std::string::npos) << "two writers' bytes in one file";
    for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "out.bin");
}

TEST(FileLock, OneHolderAtATimeAndTheLockDiesWithItsProcess) {
    const auto path = test::scratchDir("file_lock") / "locks" / "asset.lock";
    {
        auto first = FileLock::tryAcquire(path);
        ASSERT_TRUE(first);
        EXPECT_FALSE(FileLock::tryAcquire(path));
    }
    EXPECT_TRUE(FileLock::tryAcquire(path));

    // A child takes the lock and is killed with SIGKILL: nothing it could run releases it.
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0) {
        auto held = FileLock::tryAcquire(path);
        const char ok = held ? '1' : '0';
        (void)!write(ready[1], &ok, 1);
        pause();
        _exit(0);
    }
    char ok = 0;
    ASSERT_EQ(read(ready[0], &ok, 1), 1);
    EXPECT_EQ(ok, '1');
    EXPECT_FALSE(FileLock::tryAcquire(path)) << "the child holds it";
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    EXPECT_TRUE(FileLock::tryAcquire(path)) << "the killed child's lock outlived it";
}

TEST(Manifest, LinesSplitIntoWordsWithQuotes) {
    using simplify::splitManifestLine;
    EXPECT_EQ(splitManifestLine("a.obj --faces 200"), (std::vector<std::string>{"a.obj", "--faces", "200"}));
    EXPECT_EQ(splitManifestLine("\"scans/statue 01.obj\"\t--faces '2 0'"),
              (std::vector<std::string>{"scans/statue 01.obj", "--faces", "2 0"}));
    EXPECT_EQ(splitManifestLine("''"), (std::vector<std::string>{""}));
    EXPECT_THROW(splitManifestLine("\"open"), Error);
    EXPECT_THROW(splitManifestLine(std::string("a\0b", 3)), Error);
    EXPECT_THROW(splitManifestLine("a\rb"), Error);
}

TEST(Manifest, ReadsAssetsWithLineNumbersAndResolvedPaths) {
    const auto dir = test::scratchDir("manifest");
    std::ofstream(dir / "m.txt") << "# comment\n\n  sub/a.obj --faces 10\r\n/abs/b.obj\n";
    const auto lines = simplify::readManifest(dir / "m.txt");
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].number, 3);
    EXPECT_EQ(lines[0].resolved, dir / "sub/a.obj");
    EXPECT_EQ(lines[0].options, (std::vector<std::string>{"--faces", "10"}));
    EXPECT_EQ(lines[1].resolved, fs::path("/abs/b.obj"));
    std::ofstream(dir / "bad.txt") << "ok.obj\n\"unterminated.obj\n";
    try {
        simplify::readManifest(dir / "bad.txt");
        FAIL() << "an unterminated quote was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:2: unterminated"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace subdfit::io
