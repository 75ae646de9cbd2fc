// libFuzzer entry point: any bytes given to loadCharacterFromMemory must either load or throw
// GltfError; a crash, a sanitizer report, a leak or any other exception is a finding.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "throng/gltf/GltfLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::uint8_t> bytes(data, data + size);
    throng::GltfLoadOptions options;
    options.allowExternalFiles = false;  // the input is all there is
    options.limits.maxFileBytes = 8u << 20;
    options.limits.maxAccessorValues = 1u << 20;
    options.limits.maxImagePixels = 1u << 20;
    options.limits.maxClipDuration = 600.0;
    options.sklsrootSampleRate = 5.0;  // keeps each input fast; the sampling itself is not under test
    try {
        (void)throng::loadCharacterFromMemory(bytes, "fuzz.glb", options);
    } catch (const throng::GltfError&) {
    }
    return 0;
}
