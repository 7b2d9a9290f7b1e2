// One writer per output folder: the lock every writing command takes, temporary names unique
// per process, the rename's own reason in errors, and no empty folder left by a failed run.
#include "cli_runner.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/output_folder.h"
#include "test_support.h"
#include <bmfr/error.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

TEST(OutputFolder, ASecondWriterIsRefusedAndTheFirstsFolderIsUntouched) {
    const fs::path dir = testing::freshDir("out", "lock");
    {
        const OutputFolder held(dir.string(), "bmfr denoise in -o out");
        const std::string why = errorOf([&] { OutputFolder second(dir.string(), "x"); });
        EXPECT_NE(why.find("another run is writing to " + dir.string()), std::string::npos) << why;
        EXPECT_NE(why.find("pid " + std::to_string(::getpid()) + ": bmfr denoise in -o out"),
                  std::string::npos)
            << why;
        // The command line: refused at once, exit 1, nothing written.
        ASSERT_EQ(testing::runCli("synth -o " + (dir / "seq").string() +
                                  " --width 16 --height 8 --frames 2 -q")
                      .code,
                  0);
        const testing::CliResult r =
            testing::runCli("denoise " + (dir / "seq").string() + " -o " + dir.string() + " -q");
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_NE(r.output.find("another run is writing to"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "denoised_0000.exr"));
        EXPECT_FALSE(fs::exists(dir / "report.json"));
    }
    // Released: the lock file is gone and the next writer gets the folder.
    EXPECT_FALSE(fs::exists(dir / kOutputLockFile));
    EXPECT_NO_THROW(OutputFolder(dir.string(), "again"));
    EXPECT_FALSE(isEmptyOutputFolder((dir / "seq").string()));
}

TEST(OutputFolder, AFolderMadeAndLeftEmptyIsRemoved) {
    const fs::path base = testing::freshDir("out", "made");
    const fs::path deep = base / "a" / "b" / "c";
    { const OutputFolder f(deep.string() + "/", "test"); }
    EXPECT_FALSE(fs::exists(base / "a")) << "the folders it made stay behind";
    EXPECT_TRUE(fs::exists(base));
    {
        const OutputFolder f(deep.string(), "test");
        std::ofstream(deep / "result.txt") << "kept";
    }
    EXPECT_TRUE(fs::exists(deep / "result.txt"));
    EXPECT_FALSE(isEmptyOutputFolder(base.string()));
    // (A command that fails at its first frame: Hardening.AFrameBrokenInItsPixels...)
    // A folder that was there already stays, even when left empty.
    const fs::path existing = testing::freshDir("out", "existing");
    { const OutputFolder f(existing.string(), "test"); }
    EXPECT_TRUE(fs::is_directory(existing));
}

TEST(OutputFolder, TemporaryNamesAreUniquePerProcessAndCall) {
    const std::string a = temporaryPathFor("/x/y.exr"), b = temporaryPathFor("/x/y.exr");
    EXPECT_NE(a, b);
    EXPECT_NE(a.find("." + std::to_string(::getpid()) + "-"), std::string::npos) << a;
    EXPECT_EQ(a.substr(a.size() - 5), ".part");
}

TEST(OutputFolder, AFailedRenameReportsItsOwnReason) {
    const fs::path dir = testing::freshDir("out", "rename");
    fs::create_directories(dir / "taken.json"); // a folder where the file should go
    const std::string why =
        errorOf([&] { writeFileAtomically((dir / "taken.json").string(), std::string("{}")); });
    EXPECT_NE(why.find("cannot write " + (dir / "taken.json").string() + ": Is a directory"),
              std::string::npos)
        << why;
    EXPECT_EQ(why.find("Success"), std::string::npos) << why;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename(), "taken.json") << "a temporary file was left: " << e.path();
    // Through the command line, as the reproducer does it.
    writeExr((dir / "in.exr").string(), ImageF(4, 3, 3));
    const testing::CliResult r = testing::runCli("tonemap " + (dir / "in.exr").string() + " -o " +
                                                 (dir / "taken.json").string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(r.output.find("Success"), std::string::npos) << r.output;
}

} // namespace
} // namespace bmfr
