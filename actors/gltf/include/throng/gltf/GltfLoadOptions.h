#pragma once
// How the glTF loader reads a file: where external files may come from, whether images are decoded,
// resource limits, and the Sklsroot sphere parameters of the templates it builds.

#include <string>
#include <vector>

#include "throng/gltf/GltfLimits.h"

namespace throng {

/// One geometric level of a skinned character, made by simplifying its mesh (meshoptimizer).
struct GltfLodLevel {
    double maxDistance = 0.0;    ///< end of the level's range (eye distance, metres after `scale`)
    double triangleShare = 1.0;  ///< share of the mesh's triangles kept, in (0, 1]
};

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
    /// Uniform scale applied to the whole file, folded into the skeleton like a scaling parent
    /// node (Fox is modelled in centimetres: 0.01 gives metres).
    double scale = 1.0;
    /// vaLod levels of each skinned mesh, nearest first, distances increasing; empty: the mesh as
    /// it is, at every distance. A share of 1 is the mesh itself.
    std::vector<GltfLodLevel> lodLevels;
    /// Skeletal LOD of skinned characters: a joint switches off (its DOFs are not evaluated, its
    /// subtree not traversed; its vertices follow the nearest active ancestor) where the part it
    /// moves subtends less than this angle, radians. 0: every joint stays on. 0.004 is about 3
    /// pixels of a 1280 x 720 view with a 55 degree field of view.
    double jointMinAngle = 0.0;
    /// Give each skinned mesh's vertices body regions (bodyRegions: skin, hair, top, bottom by
    /// height in the bind pose, hands by joint name), for actors recoloured per region (BodyLook).
    bool bodyRegions = false;
};

}  // namespace throng
