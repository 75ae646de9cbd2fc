// libFuzzer entry point: any bytes as a glTF character that a scene declares as a template, through
// throng-town's start-up (StartUp.h): loaded, built into a template with geometric LOD levels,
// skeletal LOD and body regions (looks), eight of it standing and four flying, stepped and culled. A bad file must be a
// SceneError at /templates/x/gltf (or a documented runtime error), never a crash. (The loader alone,
// with its limits, is fuzz_gltf's.)

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "StartUp.h"
#include "throng/sim/CrowdLooks.h"

namespace {

// One file per fuzzing process, rewritten for every input.
const std::filesystem::path& inputFile() {
    static const std::filesystem::path path = [] {
        const auto folder = std::filesystem::temp_directory_path() / ("throng-fuzz-glb-" + std::to_string(::getpid()));
        std::filesystem::create_directories(folder);
        return folder / "input.glb";
    }();
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > (4u << 20)) return 0;  // the start-up of a large character is the loader fuzzer's and the tests' business
    {
        std::ofstream out(inputFile(), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    using namespace throng::sim;
    SceneDescription scene;
    TemplateDescription t;
    t.gltf = inputFile().string();
    t.lod = {{10.0, 1.0}, {std::numeric_limits<double>::infinity(), 0.3}};
    t.jointMinAngle = 0.004;
    t.looks = generatedLooks(4);  // body regions from whatever skin the file has
    scene.templates["x"] = t;
    ActorGroupDescription standing;
    standing.name = "standing";
    standing.templateName = "x";
    standing.count = 8;
    standing.behaviour = "idle";
    standing.groupSize = {2, 4};
    standing.area.size = {20.0, 20.0};
    ActorGroupDescription flying = standing;
    flying.name = "flying";
    flying.count = 4;
    flying.behaviour = "flight";
    scene.actors = {standing, flying};
    scene.camera.path = {CameraKey{0.0, {0.0, 3.0, 15.0}, {0.0, 1.0, 0.0}}};
    throng::fuzz::startUp(scene);
    return 0;
}
