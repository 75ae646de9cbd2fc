#include "throng/actors/BodyRegions.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "throng/scenegraph/BodyLook.h"

namespace throng {
namespace {

bool handLike(std::string name) {
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* part : {"hand", "wrist", "finger", "thumb", "palm"})
        if (name.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

std::vector<std::uint8_t> bodyRegions(const MeshData& mesh, std::span<const float> height, std::span<const std::string> jointNames,
                                      const BodyRegionBands& bands) {
    if (height.size() != mesh.vertexCount())
        throw std::invalid_argument("bodyRegions: mesh '" + mesh.name + "': " + std::to_string(height.size()) + " heights for " +
                                    std::to_string(mesh.vertexCount()) + " vertices");
    float low = std::numeric_limits<float>::infinity(), high = -low;
    bool finite = true;
    for (float h : height) low = std::min(low, h), high = std::max(high, h), finite = finite && std::isfinite(h);
    if (!(low < high) || !finite)
        throw std::invalid_argument("bodyRegions: mesh '" + mesh.name + "': the figure's heights are empty or not finite");
    std::vector<bool> hand(jointNames.size());
    for (std::size_t k = 0; k < jointNames.size(); ++k) hand[k] = handLike(jointNames[k]);
    std::vector<std::uint8_t> out(mesh.vertexCount());
    for (std::size_t v = 0; v < out.size(); ++v) {
        if (mesh.skinned()) {
            const std::uint32_t joint = mesh.strongestJoint(v);
            if (joint >= hand.size())
                throw std::invalid_argument("bodyRegions: mesh '" + mesh.name + "': vertex " + std::to_string(v) +
                                            " names joint " + std::to_string(joint) + " of " + std::to_string(hand.size()));
            if (hand[joint]) {
                out[v] = static_cast<std::uint8_t>(BodyRegion::Skin);
                continue;
            }
        }
        const float t = (height[v] - low) / (high - low);
        const BodyRegion r = t < bands.top ? BodyRegion::Bottom : t < bands.head ? BodyRegion::Top
                             : t < bands.hair                   ? BodyRegion::Skin
                                                                : BodyRegion::Hair;
        out[v] = static_cast<std::uint8_t>(r);
    }
    return out;
}

}  // namespace throng
