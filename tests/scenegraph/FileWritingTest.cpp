// Files written whole or not at all (WholeFile.h) and files grown by whole lines (LineFile.h): under a
// file-size limit (what a full disk looks like to a program, and can be set without privileges) a
// write fails with the system's reason, the previous content stays, and no temporary file is left.

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "throng/scenegraph/LineFile.h"
#include "throng/scenegraph/WholeFile.h"

using namespace throng;
namespace fs = std::filesystem;

namespace {

// A fresh folder per test, removed after it.
class FileWriting : public ::testing::Test {
protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() / ("throng-file-writing-" + std::to_string(::getpid()) + "-" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }

    std::string read(const fs::path& p) const {
        std::ifstream in(p, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    int filesIn() const { return int(std::distance(fs::directory_iterator(folder_), fs::directory_iterator())); }

    fs::path folder_;
};

// Limits this process's file size while alive (writes beyond fail with EFBIG, SIGXFSZ ignored).
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &saved_);
        previous_ = std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{bytes, saved_.rlim_max};
        setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, previous_);
    }

private:
    rlimit saved_{};
    void (*previous_)(int) = nullptr;
};

}  // namespace

TEST_F(FileWriting, AWholeFileReplacesTheOldOneAndLeavesNothingElse) {
    const fs::path p = folder_ / "summary.json";
    writeWholeFile(p, "first\n");
    writeWholeFile(p, "second, longer\n");
    EXPECT_EQ(read(p), "second, longer\n");
    EXPECT_EQ(filesIn(), 1) << "a temporary file was left beside it";
}

TEST_F(FileWriting, AWholeFileTooLargeForTheLimitKeepsThePreviousOne) {
    const fs::path p = folder_ / "frame.png";
    writeWholeFile(p, "the old frame");
    {
        const FileSizeLimit limit(1000);
        try {
            writeWholeFile(p, std::string(5000, 'x'));
            FAIL() << "a file over the limit was written";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("frame.png: cannot be written: File too large"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(read(p), "the old frame");
    EXPECT_EQ(filesIn(), 1) << "the temporary file was left";
}

TEST_F(FileWriting, AWholeFileInAMissingFolderNamesIt) {
    try {
        writeWholeFile(folder_ / "no-such-folder" / "a.csv", "x");
        FAIL() << "written into a folder that does not exist";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-folder/a.csv: cannot be written: No such file or directory"), std::string::npos) << e.what();
    }
}

TEST_F(FileWriting, ALineFileEndsAtItsLastWholeLine) {
    const fs::path p = folder_ / "stats.csv";
    const std::string line(60, 'a');
    int written = 0;
    {
        LineFile file(p);
        const FileSizeLimit limit(1000);
        try {
            for (; written < 100; ++written) file.append(line + "\n");
            FAIL() << "100 lines of 61 bytes went into 1000";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("stats.csv: cannot be written: File too large"), std::string::npos) << e.what();
        }
        EXPECT_EQ(file.size(), std::uint64_t(written) * 61);
    }
    EXPECT_EQ(written, 1000 / 61);
    const std::string text = read(p);
    EXPECT_EQ(text.size(), std::size_t(written) * 61) << "the partial line was not taken back";
    EXPECT_EQ(text.back(), '\n');
}
