// throng-accuracy-report on small common accuracy CSVs: the page references charts that exist, are
// PNG images of the chart's size and show more than one colour; the Pareto front and the "off"
// setting are marked in the table; crowd maps from outside the page's folder are copied beside it;
// a bad CSV stops the tool with its file and line. Where Chromium is installed, a headless
// screenshot of the page is checked too. Runs under xvfb-run (the charts are drawn by VTK).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPointData.h>

#include "throng/sim/AccuracyCsv.h"

namespace fs = std::filesystem;
using throng::sim::AccuracyCsv;
using throng::sim::AccuracyRecord;

namespace {

const fs::path kOut = fs::path(THRONG_TEST_OUTPUT_DIR) / "accuracy-report";

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs the tool with `args`; its exit code, and stderr into `err`.
int runTool(const std::string& args, std::string& err) {
    const fs::path log = kOut / "stderr.txt";
    const int status = std::system((std::string(THRONG_ACCURACY_REPORT_EXE) + " " + args + " 2> " + log.string() + " > /dev/null").c_str());
    err = readText(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

AccuracyRecord record(std::string knob, std::string value, bool off, double psnr, double ms, std::string camera) {
    AccuracyRecord r;
    r.knob = std::move(knob);
    r.value = std::move(value);
    r.off = off;
    r.metrics = {{"psnr", psnr, "dB", false}, {"pixels_off_8", 1.0 / psnr, "share", true}};
    r.ms = ms;
    r.msPhase = "draw";
    r.memoryBytes = 1024.0 * ms;
    r.scene = "fixture.json";
    r.camera = std::move(camera);
    r.actors = 100;
    return r;
}

struct Png {
    int width = 0, height = 0;
    std::set<unsigned> colours;  // distinct RGB values
};

// Reads a PNG with VTK's reader; width 0 when it is not a readable PNG.
Png readPng(const fs::path& p) {
    Png png;
    vtkNew<vtkPNGReader> reader;
    if (!reader->CanReadFile(p.string().c_str())) return png;
    reader->SetFileName(p.string().c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    int dims[3];
    image->GetDimensions(dims);
    png.width = dims[0], png.height = dims[1];
    auto* scalars = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
    if (!scalars || scalars->GetNumberOfComponents() < 3) return png;
    for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
        png.colours.insert(unsigned(scalars->GetValue(i * scalars->GetNumberOfComponents())) << 16 |
                           unsigned(scalars->GetValue(i * scalars->GetNumberOfComponents() + 1)) << 8 |
                           scalars->GetValue(i * scalars->GetNumberOfComponents() + 2));
    return png;
}

void writeGradientPng(const fs::path& p) {
    vtkNew<vtkImageData> image;
    image->SetDimensions(64, 32, 1);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            auto* px = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
            px[0] = static_cast<unsigned char>(4 * x), px[1] = static_cast<unsigned char>(8 * y), px[2] = 128;
        }
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(p.string().c_str());
    writer->SetInputData(image);
    writer->Write();
}

// The table row of `value`'s `metric` line.
std::string tableRow(const std::string& page, const std::string& value, const std::string& metric) {
    std::istringstream in(page);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("<tr", 0) == 0 && line.find("<td>" + value + "</td>") != std::string::npos &&
            line.find("<td>" + metric + "</td>") != std::string::npos)
            return line;
    return {};
}

class AccuracyReport : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        fs::remove_all(kOut);
        fs::create_directories(kOut / "csv");
        fs::create_directories(kOut / "maps");
        {
            AccuracyCsv a((kOut / "csv" / "image.csv").string());
            // Street: "2" is slower and worse than "1", so off the front; the others are on it.
            a.add(record("impostor distance", "off", true, 99.0, 10.0, "street"));
            a.add(record("impostor distance", "1", false, 40.0, 5.0, "street"));
            a.add(record("impostor distance", "2", false, 30.0, 6.0, "street"));
            a.add(record("impostor distance", "3", false, 25.0, 2.0, "street"));
            a.add(record("impostor distance", "off", true, 99.0, 8.0, "overview"));
            a.add(record("impostor distance", "1", false, 45.0, 4.0, "overview"));
        }
        {
            AccuracyCsv b((kOut / "csv" / "lod.csv").string());
            for (double scale : {0.5, 1.0, 2.0}) {
                AccuracyRecord r;
                r.knob = "lod scale";
                r.value = std::to_string(scale);
                r.metrics = {{"joint_error_mean", 3.0 * scale, "mm", true}};
                r.ms = 4.0 / scale;
                r.msPhase = "app_cull";
                r.scene = "built-in";
                r.camera = "street";
                r.actors = 3000;
                b.add(r);
            }
        }
        std::ofstream(kOut / "csv" / "notes.txt") << "not a CSV: ignored\n";
        writeGradientPng(kOut / "maps" / "density.png");
        writeGradientPng(kOut / "maps" / "speed.png");
        std::ofstream(kOut / "maps" / "speed_density.csv") << "people,density_per_m2,actor_frames,share,mean_speed_m_s\n"
                                                              "1,0.0625,600,0.6,1.3\n2,0.125,300,0.3,1.1\n4,0.25,100,0.1,0.7\n";
        status_ = runTool("--csv " + (kOut / "csv").string() + " --out " + (kOut / "page").string() + " --maps " + (kOut / "maps").string() +
                              " --link 'Cost model=costmodel/report.md'",
                          err_);
    }
    static inline int status_ = -1;
    static inline std::string err_;
};

TEST_F(AccuracyReport, PageReferencesValidNonBlankCharts) {
    ASSERT_EQ(status_, 0) << err_;
    const std::string page = readText(kOut / "page" / "index.html");
    ASSERT_FALSE(page.empty());
    // Every <img src="...">: found by hand, as std::regex under ASan trips GCC 12's uninitialised-use warning.
    std::vector<std::string> sources;
    const std::string tag = "<img src=\"";
    for (auto at = page.find(tag); at != std::string::npos; at = page.find(tag, at + 1)) {
        const auto begin = at + tag.size(), end = page.find('"', begin);
        if (end != std::string::npos) sources.push_back(page.substr(begin, end - begin));
    }
    ASSERT_EQ(sources.size(), 6u) << "two knob charts, two maps and two speed-density charts";
    int charts = 0;
    for (const std::string& s : sources) {
        EXPECT_FALSE(fs::path(s).is_absolute()) << s << ": the page must open from anywhere";
        const fs::path file = kOut / "page" / s;
        ASSERT_TRUE(fs::exists(file)) << s;
        const Png png = readPng(file);
        if (s.rfind("plots/", 0) == 0) {
            ++charts;
            EXPECT_EQ(png.width, 900) << s;
            EXPECT_EQ(png.height, 560) << s;
            EXPECT_GT(png.colours.size(), 5u) << s << ": a chart has axes, text and coloured series";
        } else {
            EXPECT_EQ(s.rfind("maps/", 0), 0u) << s << ": maps from outside the page's folder are copied beside it";
            EXPECT_EQ(png.width, 64) << s;
            EXPECT_GT(png.colours.size(), 100u) << s;
        }
    }
    EXPECT_EQ(charts, 4);
    EXPECT_NE(page.find("plots/crowd-speed-density.png"), std::string::npos);
    EXPECT_NE(page.find("the densest: 0.25 people per square metre"), std::string::npos);
    EXPECT_NE(page.find("href=\"costmodel/report.md\""), std::string::npos);
    EXPECT_NE(page.find(AccuracyCsv::header()), std::string::npos) << "the schema";
}

TEST_F(AccuracyReport, TableMarksParetoFrontAndOff) {
    ASSERT_EQ(status_, 0) << err_;
    const std::string page = readText(kOut / "page" / "index.html");
    const auto onFront = [](const std::string& row) { return row.find("class=\"front\"") != std::string::npos; };
    const std::string worse = tableRow(page, "2", "psnr"), faster = tableRow(page, "3", "psnr"), off = tableRow(page, "off", "psnr");
    ASSERT_FALSE(worse.empty());
    EXPECT_FALSE(onFront(worse)) << worse;
    EXPECT_TRUE(onFront(faster)) << faster;
    EXPECT_TRUE(onFront(off)) << off;
    EXPECT_NE(off.find("<td>off</td><td>psnr</td>"), std::string::npos) << off;
    // Each metric has its own front: lower is better for pixels off, and "2" is still beaten.
    EXPECT_FALSE(onFront(tableRow(page, "2", "pixels_off_8")));
    // Every line of both files is in the table.
    std::size_t rows = 0;
    for (const char* file : {"<td>image.csv:", "<td>lod.csv:"})
        for (std::size_t at = page.find(file); at != std::string::npos; at = page.find(file, at + 1)) ++rows;
    EXPECT_EQ(rows, 6u * 2u + 3u);
}

TEST_F(AccuracyReport, BadCsvNamesFileAndLine) {
    fs::create_directories(kOut / "bad");
    {
        AccuracyCsv a((kOut / "bad" / "broken.csv").string());
        a.add(record("knob", "1", false, 30.0, 1.0, "street"));
    }
    std::ofstream(kOut / "bad" / "broken.csv", std::ios::app) << "knob,2,0,psnr,not-a-number,dB,higher,1,draw,0,s,street,1\n";
    std::string err;
    EXPECT_EQ(runTool("--csv " + (kOut / "bad").string() + " --out " + (kOut / "bad-page").string(), err), 1);
    EXPECT_NE(err.find("broken.csv:4"), std::string::npos) << err;  // header, two metric lines, then the bad one
    EXPECT_NE(err.find("error"), std::string::npos) << err << ": names the column";
    EXPECT_FALSE(fs::exists(kOut / "bad-page" / "index.html"));

    std::ofstream(kOut / "bad" / "broken.csv") << "knob,value,psnr\nx,1,3\n";
    EXPECT_EQ(runTool("--csv " + (kOut / "bad").string() + " --out " + (kOut / "bad-page").string(), err), 1);
    EXPECT_NE(err.find("broken.csv:1"), std::string::npos) << err;

    // A broken speed_density.csv beside the maps stops the page too, naming its line.
    fs::create_directories(kOut / "bad-maps");
    std::ofstream(kOut / "bad-maps" / "speed_density.csv") << "people,density_per_m2,actor_frames,share,mean_speed_m_s\n1,0.0625,many,1,1\n";
    EXPECT_EQ(runTool("--csv " + (kOut / "csv").string() + " --out " + (kOut / "bad-page").string() + " --maps " + (kOut / "bad-maps").string(), err), 1);
    EXPECT_NE(err.find("speed_density.csv:2: field 3 ('many')"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(kOut / "bad-page" / "index.html"));

    fs::create_directories(kOut / "empty");
    EXPECT_EQ(runTool("--csv " + (kOut / "empty").string() + " --out " + (kOut / "bad-page").string(), err), 1);
    EXPECT_NE(err.find("no .csv file"), std::string::npos) << err;
    EXPECT_EQ(runTool("--csv " + (kOut / "missing").string(), err), 2) << "a bad command line";
}

TEST_F(AccuracyReport, ChromiumScreenshotIsNotBlank) {
    ASSERT_EQ(status_, 0) << err_;
    const char* chromium = "/usr/bin/chromium";
    if (!fs::exists(chromium)) GTEST_SKIP() << "Chromium is not installed: no screenshot of the page";
    const fs::path shot = kOut / "page.png";
    fs::remove(shot);
    const std::string command = std::string(chromium) + " --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,1600 "
                                "--screenshot=" + shot.string() + " file://" + fs::absolute(kOut / "page" / "index.html").string() +
                                " > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const Png png = readPng(shot);
    EXPECT_EQ(png.width, 1200);
    EXPECT_EQ(png.height, 1600);
    EXPECT_GT(png.colours.size(), 50u) << "the page shows text and charts";
}

}  // namespace
