// The common accuracy CSV: what is written reads back the same, bad records are refused before a
// line is written, and a damaged file is named with its line and column.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "throng/sim/AccuracyCsv.h"

using namespace throng::sim;

namespace {

std::string outputPath(const std::string& name) {
    std::filesystem::create_directories(THRONG_TEST_OUTPUT_DIR);
    return std::string(THRONG_TEST_OUTPUT_DIR) + "/" + name;
}

AccuracyRecord sample() {
    AccuracyRecord r;
    r.knob = "lod scale";
    r.value = "0.5, coarse";  // a comma: must be quoted
    r.metrics = {{"psnr", 31.25, "dB", false}, {"pixels_off_8", 0.0125, "share", true}};
    r.ms = 3.5;
    r.msPhase = "app_cull+draw";
    r.memoryBytes = 1024;
    r.scene = "default.json";
    r.camera = "street";
    r.actors = 2000;
    return r;
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST(AccuracyCsv, WrittenRecordsReadBackOneRowPerMetric) {
    const std::string path = outputPath("roundtrip.csv");
    {
        AccuracyCsv csv(path);
        csv.add(sample());
        AccuracyRecord off = sample();
        off.value = "1";
        off.off = true;
        off.metrics = {{"psnr", 99, "dB", false}};
        csv.add(off);
    }
    const auto rows = readAccuracyCsv(path);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].knob, "lod scale");
    EXPECT_EQ(rows[0].value, "0.5, coarse");
    EXPECT_FALSE(rows[0].off);
    EXPECT_EQ(rows[0].metric.name, "psnr");
    EXPECT_DOUBLE_EQ(rows[0].metric.value, 31.25);
    EXPECT_FALSE(rows[0].metric.lowerIsBetter);
    EXPECT_EQ(rows[1].metric.name, "pixels_off_8");
    EXPECT_TRUE(rows[1].metric.lowerIsBetter);
    EXPECT_DOUBLE_EQ(rows[1].ms, 3.5);
    EXPECT_EQ(rows[1].msPhase, "app_cull+draw");
    EXPECT_EQ(rows[1].camera, "street");
    EXPECT_EQ(rows[1].actors, 2000);
    EXPECT_EQ(rows[1].line, 3);
    EXPECT_TRUE(rows[2].off);
}

TEST(AccuracyCsv, BadRecordsAreRefusedBeforeAnythingIsWritten) {
    const std::string path = outputPath("refused.csv");
    AccuracyCsv csv(path);
    AccuracyRecord nan = sample();
    nan.metrics[1].value = std::numeric_limits<double>::quiet_NaN();
    try {
        csv.add(nan);
        FAIL() << "a NaN metric was written";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("pixels_off_8"), std::string::npos) << e.what();
    }
    AccuracyRecord negative = sample();
    negative.ms = -1;
    EXPECT_THROW(csv.add(negative), std::invalid_argument);
    AccuracyRecord none = sample();
    none.metrics.clear();
    EXPECT_THROW(csv.add(none), std::invalid_argument);
    AccuracyRecord unnamed = sample();
    unnamed.knob.clear();
    EXPECT_THROW(csv.add(unnamed), std::invalid_argument);
    EXPECT_TRUE(readAccuracyCsv(path).empty());  // not even the good first metric of the NaN record
}

TEST(AccuracyCsv, DamagedFilesAreNamedWithLineAndColumn) {
    const auto message = [](const std::string& path) -> std::string {
        try {
            readAccuracyCsv(path);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    };
    const std::string missing = outputPath("accuracy-csv-never-written.csv");
    std::filesystem::remove(missing);
    EXPECT_NE(message(missing).find("cannot read"), std::string::npos) << message(missing);
    const std::string header = std::string(AccuracyCsv::header()) + "\n";
    const std::string good = "k,v,0,psnr,30,dB,higher,1,draw,0,s.json,street,10\n";
    const std::string wrongHeader = outputPath("wrong-header.csv");
    writeText(wrongHeader, "knob,value,psnr\n");
    EXPECT_NE(message(wrongHeader).find(":1:"), std::string::npos);
    const std::string shortLine = outputPath("short-line.csv");
    writeText(shortLine, header + good + "k,v,0,psnr\n");
    EXPECT_NE(message(shortLine).find(":3: 4 fields"), std::string::npos) << message(shortLine);
    const std::string badNumber = outputPath("bad-number.csv");
    writeText(badNumber, header + "k,v,0,psnr,inf,dB,higher,1,draw,0,s.json,street,10\n");
    EXPECT_NE(message(badNumber).find(":2: column 'error'"), std::string::npos) << message(badNumber);
    const std::string badBetter = outputPath("bad-better.csv");
    writeText(badBetter, header + "k,v,0,psnr,30,dB,up,1,draw,0,s.json,street,10\n");
    EXPECT_NE(message(badBetter).find("column 'better'"), std::string::npos) << message(badBetter);
    const std::string badCount = outputPath("bad-count.csv");
    writeText(badCount, header + "k,v,0,psnr,30,dB,higher,1,draw,0,s.json,street,2.5\n");
    EXPECT_NE(message(badCount).find("column 'actors'"), std::string::npos) << message(badCount);
}
