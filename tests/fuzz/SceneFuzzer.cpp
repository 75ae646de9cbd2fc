// libFuzzer entry point: any bytes as a scene file. Parsing must either give a description or throw
// SceneError; a description small enough to build per input then goes through throng-town's start-up
// (StartUp.h). Paths in the scene resolve against the shared assets (THRONG_FUZZ_ASSETS), as the
// committed corpus (corpus/scene) writes them.

#include <cstddef>
#include <cstdint>
#include <string>

#include "StartUp.h"
#include "throng/sim/SceneParser.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    throng::sim::SceneDescription scene;
    try {
        scene = throng::sim::parseScene(text, THRONG_FUZZ_ASSETS, "fuzz.json");
    } catch (const throng::sim::SceneError&) {
        return 0;
    }
    if (throng::fuzz::smallEnough(scene)) throng::fuzz::startUp(scene);
    return 0;
}
