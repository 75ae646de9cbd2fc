#include "throng/render/ViewWarp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat2x3.hpp>
#include <glm/mat3x2.hpp>
#include <glm/matrix.hpp>

#include "throng/render/FeatureTrack.h"
#include "throng/render/GpuMorpher.h"

namespace throng {
namespace {

void checkWeights(std::span<const float> weights, const char* who) {
    float sum = 0.0f;
    for (float w : weights) {
        if (!(w >= 0.0f) || !std::isfinite(w)) throw std::invalid_argument(std::string(who) + ": a weight is negative or not finite");
        sum += w;
    }
    if (!(sum > 0.0f)) throw std::invalid_argument(std::string(who) + ": the weights sum to zero");
}

}  // namespace

std::vector<FeatureLine> blendViewLines(std::span<const std::vector<FeatureLine>> views, std::span<const float> weights) {
    if (views.empty() || views.size() != weights.size())
        throw std::invalid_argument("blendViewLines: " + std::to_string(views.size()) + " views and " + std::to_string(weights.size()) +
                                    " weights");
    std::vector<FeatureLine> out(views.front().size());
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (views[v].size() != out.size()) throw std::invalid_argument("blendViewLines: the views have different line counts");
        for (std::size_t i = 0; i < out.size(); ++i) {
            out[i].p += weights[v] * views[v][i].p;
            out[i].q += weights[v] * views[v][i].q;
        }
    }
    return out;
}

glm::mat2 viewPostwarp(std::span<const glm::vec3> viewDirections, std::span<const float> weights, const glm::vec3& toEye) {
    if (viewDirections.empty() || viewDirections.size() != weights.size())
        throw std::invalid_argument("viewPostwarp: " + std::to_string(viewDirections.size()) + " views and " +
                                    std::to_string(weights.size()) + " weights");
    // Image offsets are (x, y down) = (right . r, -up . r) * scale for an offset r from the centre:
    // the blended camera's rows are the weighted sums of the views' rows.
    glm::vec3 right(0.0f), down(0.0f);
    for (std::size_t i = 0; i < viewDirections.size(); ++i) {
        const ViewBasis b = viewBasis(viewDirections[i]);
        right += weights[i] * b.right;
        down -= weights[i] * b.up;
    }
    const ViewBasis eye = viewBasis(toEye);
    // M A = B with A = [right; down] (2x3, the blended camera) and B the eye's camera, least squares:
    // M = B A^T (A A^T)^-1.
    const glm::mat3x2 a = glm::transpose(glm::mat2x3(right, down));
    const glm::mat3x2 b = glm::transpose(glm::mat2x3(eye.right, -eye.up));
    const glm::mat2 aat = a * glm::transpose(a);
    if (!(std::fabs(glm::determinant(aat)) > 1e-12f)) return glm::mat2(1.0f);
    return b * glm::transpose(a) * glm::inverse(aat);
}

std::vector<FeatureLine> postwarpLines(std::span<const FeatureLine> lines, const glm::mat2& m, int cellSize) {
    const glm::vec2 c(0.5f * static_cast<float>(cellSize));
    std::vector<FeatureLine> out(lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) out[i] = {c + m * (lines[i].p - c), c + m * (lines[i].q - c)};
    return out;
}

Image warpViews(std::span<const Image> cells, std::span<const std::vector<FeatureLine>> lines, std::span<const float> weights,
                std::span<const FeatureLine> target, const MorphParameters& parameters, std::span<const LineAttributes> attributes,
                GpuMorpher* gpu) {
    if (cells.empty() || cells.size() != lines.size() || cells.size() != weights.size())
        throw std::invalid_argument("warpViews: " + std::to_string(cells.size()) + " cells, " + std::to_string(lines.size()) + " line sets, " +
                                    std::to_string(weights.size()) + " weights");
    checkWeights(weights, "warpViews");
    float sum = 0.0f;
    for (float w : weights) sum += w;
    std::vector<float> acc(cells.front().rgba.size(), 0.0f);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        if (!cells[i].valid() || cells[i].width != cells.front().width || cells[i].height != cells.front().height)
            throw std::invalid_argument("warpViews: cell " + std::to_string(i) + " is invalid or of another size");
        if (lines[i].size() != target.size())
            throw std::invalid_argument("warpViews: cell " + std::to_string(i) + " has " + std::to_string(lines[i].size()) + " lines for " +
                                        std::to_string(target.size()) + " target lines");
        if (weights[i] <= 0.0f) continue;
        const Image warped = gpu && target.size() <= GpuMorpher::kMaxLines
                                 ? gpu->morph(cells[i], lines[i], cells[i], lines[i], target, 0.0f, parameters, attributes)
                                 : morphImages(cells[i], lines[i], cells[i], lines[i], target, 0.0f, parameters, 1, attributes);
        const float w = weights[i] / sum;
        for (std::size_t j = 0; j < acc.size(); ++j) acc[j] += w * static_cast<float>(warped.rgba[j]);
    }
    Image out = cells.front();
    out.name = "view warp";
    for (std::size_t j = 0; j < acc.size(); ++j) out.rgba[j] = static_cast<std::uint8_t>(std::clamp(std::lround(acc[j]), 0L, 255L));
    return out;
}

}  // namespace throng
