#include "throng/testkit/ImageSimilarity.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace throng::testkit {
namespace {

void check(const Image& a, const Image& b, const char* who) {
    if (!a.valid() || !b.valid()) throw std::invalid_argument(std::string(who) + ": an image is invalid");
    if (a.width != b.width || a.height != b.height) throw std::invalid_argument(std::string(who) + ": sizes differ");
}

bool covered(const Image& a, const Image& b, std::size_t pixel) { return a.rgba[pixel * 4 + 3] > 0 || b.rgba[pixel * 4 + 3] > 0; }

}  // namespace

double normalizedCrossCorrelation(const Image& a, const Image& b, bool coveredOnly) {
    check(a, b, "normalizedCrossCorrelation");
    const std::size_t pixels = static_cast<std::size_t>(a.width) * a.height;
    double sa = 0, sb = 0, n = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (!coveredOnly || covered(a, b, i))
            for (int c = 0; c < 4; ++c) sa += a.rgba[i * 4 + c], sb += b.rgba[i * 4 + c], n += 1;
    if (n == 0) return 1.0;
    const double ma = sa / n, mb = sb / n;
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (!coveredOnly || covered(a, b, i))
            for (int c = 0; c < 4; ++c) {
                const double da = a.rgba[i * 4 + c] - ma, db = b.rgba[i * 4 + c] - mb;
                ab += da * db, aa += da * da, bb += db * db;
            }
    if (aa == 0 || bb == 0) return aa == bb ? 1.0 : 0.0;
    return ab / std::sqrt(aa * bb);
}

double structuralSimilarity(const Image& a, const Image& b) {
    check(a, b, "structuralSimilarity");
    const auto luminance = [](const Image& im) {
        std::vector<double> l(static_cast<std::size_t>(im.width) * im.height);
        for (std::size_t i = 0; i < l.size(); ++i)
            l[i] = 0.299 * im.rgba[i * 4] + 0.587 * im.rgba[i * 4 + 1] + 0.114 * im.rgba[i * 4 + 2];
        return l;
    };
    const std::vector<double> la = luminance(a), lb = luminance(b);
    constexpr int kWindow = 8, kStride = 4;
    constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double sum = 0;
    int windows = 0;
    for (int y0 = 0; y0 + kWindow <= a.height; y0 += kStride)
        for (int x0 = 0; x0 + kWindow <= a.width; x0 += kStride) {
            bool any = false;
            double ma = 0, mb = 0;
            for (int y = y0; y < y0 + kWindow; ++y)
                for (int x = x0; x < x0 + kWindow; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * a.width + x;
                    any = any || covered(a, b, i);
                    ma += la[i], mb += lb[i];
                }
            if (!any) continue;
            constexpr double n = kWindow * kWindow;
            ma /= n, mb /= n;
            double va = 0, vb = 0, cov = 0;
            for (int y = y0; y < y0 + kWindow; ++y)
                for (int x = x0; x < x0 + kWindow; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * a.width + x;
                    va += (la[i] - ma) * (la[i] - ma), vb += (lb[i] - mb) * (lb[i] - mb), cov += (la[i] - ma) * (lb[i] - mb);
                }
            va /= n - 1, vb /= n - 1, cov /= n - 1;
            sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            ++windows;
        }
    return windows == 0 ? 1.0 : sum / windows;
}

}  // namespace throng::testkit
