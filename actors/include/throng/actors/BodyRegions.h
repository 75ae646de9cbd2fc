#pragma once
// Which body region (skin, hair, top, bottom) each vertex of a character belongs to, for crowd
// diversity (BodyLook). Made from the bind pose, not painted: a vertex's height in the figure
// chooses between bottom, top, skin (the head) and hair (its crown), and vertices carried mostly by
// a hand, finger or wrist joint are skin. Suits upright figures; a quadruped gets bands along its
// height (legs, body, head) that still recolour as a whole.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "throng/scenegraph/MeshData.h"

namespace throng {

/// Where the regions start, as shares of the figure's height from its lowest vertex.
struct BodyRegionBands {
    float top = 0.48f;   ///< below: bottom (legs, hips)
    float head = 0.84f;  ///< below: top (torso, arms)
    float hair = 0.94f;  ///< below: skin (face, neck); above: hair
};

/// The region (BodyRegion) of every vertex of `mesh`, `height[v]` being vertex v's height in the
/// upright figure (its rest pose with +Y up: a mesh's own frame may lie on its side). `jointNames[k]`
/// names skin joint k: a vertex whose strongest influence is a joint named like a hand ("hand",
/// "wrist", "finger", "thumb", "palm", any case) is skin. Throws std::invalid_argument naming the
/// mesh if the heights are not one per vertex, all equal or not finite, or a joint index has no name.
std::vector<std::uint8_t> bodyRegions(const MeshData& mesh, std::span<const float> height, std::span<const std::string> jointNames,
                                      const BodyRegionBands& bands = {});

}  // namespace throng
