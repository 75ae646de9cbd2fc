// throng-demo: builds a scene of a few thousand generic nodes (animated figures with three levels of
// detail on a field), runs APP / matrices-and-bounds / CULL / DRAW for some frames with a moving
// camera, and prints per-phase statistics and the FMULT accounting of one frame.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/RecordingBackend.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/testkit/FigureField.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"

using namespace throng;

namespace {

struct Options {
    int figures = 1000;
    int frames = 300;
};

std::size_t countNodes(const Node& node) {
    std::size_t n = 1;
    if (auto* g = dynamic_cast<const Group*>(&node))
        for (const auto& c : g->children()) n += countNodes(*c);
    return n;
}

struct PhaseSummary {
    std::vector<double> samples;
    void add(double v) { samples.push_back(v); }
    void print(const char* name) {
        std::sort(samples.begin(), samples.end());
        double sum = 0;
        for (double s : samples) sum += s;
        std::printf("  %-18s mean %8.3f ms   median %8.3f ms   max %8.3f ms\n", name,
                    sum / static_cast<double>(samples.size()), samples[samples.size() / 2], samples.back());
    }
};

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    support::CommandLine cl("throng-demo",
                            "A headless scenegraph demo: animated figures on a field under traditional processing,\n"
                            "with per-phase statistics and the FMULT accounting of the last frame.");
    cl.app().add_option("--figures", opt.figures, "animated figures on the field (each is 14 nodes)")
        ->type_name("N")
        ->check(support::wholeNumber(1, 10'000'000));
    cl.app().add_option("--frames", opt.frames, "frames to run")->type_name("N")->check(support::wholeNumber(1, 10'000'000));
    if (const auto code = cl.parse(argc, argv)) return *code;
    auto scene = testkit::buildFigureField(opt.figures);
    const double extent = testkit::figureFieldExtent(opt.figures);
    std::printf("throng-demo: %d figures, %zu nodes, %d frames (traditional processing, headless)\n",
                opt.figures, countNodes(*scene), opt.frames);

    Camera camera;
    camera.setPerspective(std::numbers::pi / 3.0, 16.0 / 9.0, 0.1, 3000.0);
    TraditionalProcessor processor;
    RecordingBackend backend;
    PhaseSummary app, matrices, cull, draw;
    std::uint64_t items = 0, primitives = 0, rejected = 0, tested = 0;
    const double dt = 1.0 / 60.0;
    for (int f = 0; f < opt.frames; ++f) {
        const double t = f * dt;
        // The camera circles the field, looking at its centre.
        const double a = 0.2 * t;
        const Vec3 centre(extent / 2, 0, extent / 2);
        camera.setLookAt(centre + Vec3(extent * 0.6 * std::cos(a), 25.0, extent * 0.6 * std::sin(a)), centre);
        processor.counter().setEnabled(f == opt.frames - 1);  // count the last frame only
        const FrameStatistics& s = processor.processFrame(*scene, camera, t, &backend);
        if (f == opt.frames - 1) break;  // the counted frame is reported separately
        app.add(s.appMs);
        matrices.add(s.matricesBoundsMs);
        cull.add(s.cullMs);
        draw.add(s.drawMs);
        items += s.cull.drawItems;
        primitives += s.cull.primitives;
        rejected += s.cull.nodesRejected;
        tested += s.cull.spheresTested;
    }
    const int timed = std::max(1, opt.frames - 1);
    std::printf("per-phase time over %d frames:\n", timed);
    if (timed > 0 && !app.samples.empty()) {
        app.print("APP");
        matrices.print("matrices+bounds");
        cull.print("CULL");
        draw.print("DRAW (recording)");
    }
    std::printf("per frame: %.0f draw items, %.0f primitives, %.0f spheres tested, %.0f nodes rejected\n",
                double(items) / timed, double(primitives) / timed, double(tested) / timed, double(rejected) / timed);

    OpCounter& c = processor.counter();
    std::printf("FMULT accounting of the last frame (categories of Table 1, seed 002):\n");
    std::printf("  %-7s %12s %14s\n", "", "operations", "FMULT");
    for (std::size_t i = 0; i < kOpCategoryCount; ++i) {
        const auto cat = static_cast<OpCategory>(i);
        std::printf("  %-7s %12llu %14llu\n", std::string(opCategoryName(cat)).c_str(),
                    static_cast<unsigned long long>(c.operations(cat)), static_cast<unsigned long long>(c.fmult(cat)));
    }
    std::printf("  %-7s %12s %14llu\n", "total", "", static_cast<unsigned long long>(c.totalFmult()));
    return 0;
}
