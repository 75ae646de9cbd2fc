#include "throng/testkit/ImageCompare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace throng::testkit {
namespace {

void check(const Image& a, const Image& b, const char* where) {
    const auto describe = [](const Image& i) {
        return "'" + i.name + "' (" + std::to_string(i.width) + " x " + std::to_string(i.height) + ")";
    };
    if (!a.valid()) throw std::invalid_argument(std::string(where) + ": image " + describe(a) + " is not valid");
    if (!b.valid()) throw std::invalid_argument(std::string(where) + ": image " + describe(b) + " is not valid");
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(std::string(where) + ": sizes differ: " + describe(a) + " and " + describe(b));
}

}  // namespace

ImageDifference compareImages(const Image& a, const Image& b, int threshold) {
    check(a, b, "compareImages");
    if (threshold < 0 || threshold > 255)
        throw std::invalid_argument("compareImages: threshold " + std::to_string(threshold) + " is outside 0-255");
    ImageDifference d;
    const std::size_t pixels = static_cast<std::size_t>(a.width) * a.height;
    std::uint64_t sumAbs = 0, sumSq = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 4; ++c) {
            const int diff = std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c]));
            worst = std::max(worst, diff);
            sumAbs += static_cast<std::uint64_t>(diff);
            sumSq += static_cast<std::uint64_t>(diff * diff);
        }
        d.maxChannelDifference = std::max(d.maxChannelDifference, worst);
        if (worst > threshold) ++d.pixelsOverThreshold;
    }
    const double samples = 4.0 * static_cast<double>(pixels);
    d.fractionOverThreshold = static_cast<double>(d.pixelsOverThreshold) / static_cast<double>(pixels);
    d.meanAbsoluteDifference = static_cast<double>(sumAbs) / samples;
    const double mse = static_cast<double>(sumSq) / samples;
    d.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
    return d;
}

Image differenceImage(const Image& a, const Image& b, int gain) {
    check(a, b, "differenceImage");
    Image out;
    out.name = "difference of '" + a.name + "' and '" + b.name + "'";
    out.width = a.width;
    out.height = a.height;
    out.rgba.resize(a.rgba.size());
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c)
            out.rgba[i + c] = static_cast<std::uint8_t>(
                std::min(255, gain * std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c]))));
        out.rgba[i + 3] = 255;
    }
    return out;
}

}  // namespace throng::testkit
