// Corrupt rawlogs: the shipped dataset truncated at many points and with bytes flipped, each
// replayed by daep-explore. Every replay ends with exit 1 and one line naming the file and
// what is wrong, keeping what it wrote (or, where the damage leaves a readable rawlog: a file
// cut exactly between objects, a flip inside pixel data, with a clean end).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "RunApp.h"

namespace {

namespace fs = std::filesystem;
using daep::test::freshDir;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runExplore;

const std::string kDataset = std::string(DAEP_SOURCE_DIR) + "/datasets/tiny_room_dynamic.rawlog";

/**
 * Where objects of the decompressed dataset start: every frame with its two poses is 59259
 * bytes, so cuts at multiples of it fall between objects.
 */
constexpr std::size_t kSecondFrame = 59259;
constexpr std::size_t kPoseAfterSecondFrame = 117526;
/** Where in a frame the range image's rows and cols (uint32 each) are. */
constexpr std::size_t kRangeImageSize = 165;

using Bytes = std::vector<char>;

Bytes readBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& p, const Bytes& b) {
    std::ofstream(p, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
}

struct Outcome {
    int exitCode;
    std::string err, summary;
};

Outcome replay(const fs::path& rawlog, const fs::path& dir) {
    const fs::path out = dir / "run";
    fs::remove_all(out);
    const auto r =
        runExplore(kTinyIni + " --set experiment.source=rawlog" +
                       " --set experiment.rawlog_file=" + rawlog.string() +
                       " --set rawlog.world=tiny_room.yaml --set rawlog.plan_every_s=100" +
                       " --set output.scene=false --quiet --out " + out.string(),
                   dir);
    return {r.exitCode, r.err, readText(out / "summary.json")};
}

int lines(const std::string& s) {
    return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

/** Exit 1 with one line naming the file, or a clean end; never a crash or exit 2. */
void expectCleanOutcome(const Outcome& o, const fs::path& rawlog, bool mustFail) {
    if (o.exitCode == 0 && !mustFail) {
        EXPECT_NE(o.summary.find("\"end_reason\": \"end of rawlog\""), std::string::npos);
        return;
    }
    ASSERT_EQ(o.exitCode, 1) << o.err;
    EXPECT_EQ(lines(o.err), 1) << o.err;
    EXPECT_NE(o.err.find(rawlog.string() + ": "), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("backtrace"), std::string::npos) << o.err;
    if (!o.summary.empty()) {  // the replay had started: its outputs are kept
        const auto at = o.summary.find("\"end_reason\": \"error: ");
        ASSERT_NE(at, std::string::npos) << o.summary;
        EXPECT_EQ(o.summary.find("\\n", at), std::string::npos) << o.summary;
    }
}

class RawlogCorruption : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = freshDir("rawlog_corrupt");
        gz_ = readBytes(kDataset);
        const fs::path plain = dir_ / "plain.rawlog";
        ASSERT_EQ(std::system(("gzip -dc " + kDataset + " > " + plain.string()).c_str()), 0);
        plain_ = readBytes(plain);
        ASSERT_GT(plain_.size(), kPoseAfterSecondFrame + 500);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const Bytes& b) const {
        writeBytes(dir_ / name, b);
        return dir_ / name;
    }

    fs::path dir_;
    Bytes gz_, plain_;
};

TEST_F(RawlogCorruption, TruncatedInsideAnObjectIsExitOneSayingTruncated) {
    const std::size_t n = plain_.size();
    for (const std::size_t cut : {std::size_t(3), std::size_t(40), std::size_t(30000),
                                  kSecondFrame + 100, n / 3 + 777, n / 2 + 12345, n - 100, n - 1}) {
        SCOPED_TRACE("plain cut at " + std::to_string(cut));
        const fs::path p = write("cut.rawlog", Bytes(plain_.begin(), plain_.begin() + cut));
        const Outcome o = replay(p, dir_);
        expectCleanOutcome(o, p, true);
        EXPECT_NE(o.err.find("truncated rawlog: the file ends inside object"), std::string::npos)
            << o.err;
        if (cut > kPoseAfterSecondFrame) {  // frame 1 was handled: outputs exist
            EXPECT_NE(o.summary.find("truncated rawlog"), std::string::npos) << o.summary;
            EXPECT_GE(lines(readText(dir_ / "run" / "trajectory.csv")), 2);
        }
    }
}

TEST_F(RawlogCorruption, CutBetweenObjectsIsAShorterRawlog) {
    const fs::path p = write("short.rawlog", Bytes(plain_.begin(), plain_.begin() + kSecondFrame));
    const Outcome o = replay(p, dir_);
    ASSERT_EQ(o.exitCode, 0) << o.err;
    EXPECT_NE(o.summary.find("\"end_reason\": \"end of rawlog\""), std::string::npos);
    EXPECT_EQ(lines(readText(dir_ / "run" / "trajectory.csv")), 2);  // header + the one frame
}

TEST_F(RawlogCorruption, TruncatedCompressedFiles) {
    const std::size_t n = gz_.size();
    for (const std::size_t cut : {std::size_t(0), std::size_t(1), std::size_t(10),
                                  std::size_t(5000), n / 4, n / 2, n - 3000}) {
        SCOPED_TRACE("gz cut at " + std::to_string(cut));
        const fs::path p = write("cut.rawlog", Bytes(gz_.begin(), gz_.begin() + cut));
        expectCleanOutcome(replay(p, dir_), p, true);
    }
}

TEST_F(RawlogCorruption, FlippedBytesInObjectHeadersAndPoses) {
    std::vector<std::size_t> at;
    for (const std::size_t off : {0, 1, 2, 5, 9, 20, 30, 36, 44, 60, 80, 100, 130})
        at.push_back(kSecondFrame + off);  // class name, version, sensor pose, timestamp...
    for (const std::size_t off : {0, 4, 12, 24, 40, 60, 90, 120, 200, 300, 400})
        at.push_back(kPoseAfterSecondFrame + off);  // the drone pose right after frame 2
    for (const std::size_t pos : at) {
        SCOPED_TRACE("flip at " + std::to_string(pos));
        Bytes b = plain_;
        b[pos] = static_cast<char>(b[pos] ^ 0xff);
        const fs::path p = write("flip.rawlog", b);
        expectCleanOutcome(replay(p, dir_), p, false);
    }
}

TEST_F(RawlogCorruption, FlippedBytesInTheCompressedStream) {
    unsigned state = 12345;  // a fixed LCG: the same positions every run
    for (int i = 0; i < 8; ++i) {
        state = state * 1103515245u + 12345u;
        const std::size_t pos = 20 + (state >> 8) % (gz_.size() - 40);
        SCOPED_TRACE("gz flip at " + std::to_string(pos));
        Bytes b = gz_;
        b[pos] = static_cast<char>(b[pos] ^ 0x5a);
        const fs::path p = write("flip.rawlog", b);
        expectCleanOutcome(replay(p, dir_), p, false);
    }
}

TEST_F(RawlogCorruption, ImageSizesBeyondMemoryAreExitOneBeforeAnythingIsAllocated) {
    // A flipped byte of the range image's row or column count asks for 4 or 5.3 GB, which MRPT
    // allocated and filled for minutes; a flipped top byte makes the count negative as an int,
    // which MRPT refuses itself.
    for (const std::size_t byte : {2, 3, 6, 7}) {
        const std::size_t pos = kSecondFrame + kRangeImageSize + byte;
        SCOPED_TRACE("flip at " + std::to_string(pos));
        Bytes b = plain_;
        b[pos] = static_cast<char>(b[pos] ^ 0xff);
        const fs::path p = write("size.rawlog", b);
        const Outcome o = replay(p, dir_);
        expectCleanOutcome(o, p, true);
        EXPECT_NE(o.err.find("corrupt rawlog: object 4 (after 0 depth frames)"), std::string::npos)
            << o.err;
        if (byte == 2 || byte == 6) {
            EXPECT_NE(o.err.find("declares more data than memory holds"), std::string::npos)
                << o.err;
        }
    }
    // Found by fuzz_rawlog: a range image of 3.7e18 bytes in a file of its own.
    const fs::path found = fs::path(DAEP_SOURCE_DIR) / "tests/fuzz/regressions/rawlog" /
                           "range_image_size_beyond_memory.rawlog";
    const Outcome o = replay(found, dir_);
    expectCleanOutcome(o, found, true);
    EXPECT_NE(o.err.find("declares more data than memory holds"), std::string::npos) << o.err;
}

TEST_F(RawlogCorruption, AFileThatIsNoRawlogLeavesNoEmptyOutputs) {
    const fs::path p = write("passwd.rawlog", Bytes{'r', 'o', 'o', 't', ':', 'x', ':', '0', '\n'});
    const Outcome o = replay(p, dir_);
    expectCleanOutcome(o, p, true);
    EXPECT_NE(o.err.find("not an MRPT rawlog"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "run" / "trajectory.csv"));
}

}  // namespace
