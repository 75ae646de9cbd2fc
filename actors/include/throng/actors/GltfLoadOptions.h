#pragma once
// How the glTF loader reads a file: where external files may come from, whether images are decoded,
// resource limits, and the Sklsroot sphere parameters of the templates it builds.

#include <string>

#include "throng/actors/GltfLimits.h"

namespace throng {

/// Options of loadCharacter / loadCharacterFromMemory.
struct GltfLoadOptions {
    /// Whether buffers and images may be read from files next to the glTF (relative URIs only;
    /// data URIs and .glb chunks are always allowed).
    bool allowExternalFiles = true;
    /// Directory external URIs are resolved against; empty: the glTF file's own directory
    /// (loadCharacterFromMemory with an empty directory refuses external files).
    std::string baseDirectory;
    /// Whether textures are decoded (PNG with stb_image, JPEG with libjpeg-turbo); off, meshes
    /// keep their base colour only (tools that do not draw save the time).
    bool decodeImages = true;
    /// Resource limits.
    GltfLimits limits;
    /// Margin added to the sampled Sklsroot radius, metres; negative: max(0.05, 1% of the rest
    /// extent), which suits characters in metres and in centimetres alike.
    double sklsrootMargin = -1.0;
    /// Rate at which clips are sampled for the Sklsroot radius, besides every key time (Hz).
    double sklsrootSampleRate = 30.0;
};

}  // namespace throng
