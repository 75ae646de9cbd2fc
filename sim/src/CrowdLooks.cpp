#include "throng/sim/CrowdLooks.h"

#include <array>
#include <cctype>
#include <stdexcept>

namespace throng::sim {
namespace {

constexpr std::array<std::uint32_t, 6> kSkin{packBodyColour(246, 214, 184), packBodyColour(226, 180, 140), packBodyColour(198, 144, 102),
                                             packBodyColour(160, 106, 70), packBodyColour(120, 78, 50), packBodyColour(84, 56, 38)};
constexpr std::array<std::uint32_t, 6> kHair{packBodyColour(30, 22, 18), packBodyColour(70, 44, 26), packBodyColour(130, 90, 50),
                                             packBodyColour(210, 170, 100), packBodyColour(150, 60, 30), packBodyColour(170, 170, 170)};
constexpr std::array<std::uint32_t, 10> kTop{packBodyColour(200, 40, 40),  packBodyColour(40, 90, 180),  packBodyColour(240, 240, 235),
                                             packBodyColour(50, 140, 70),  packBodyColour(240, 190, 40), packBodyColour(120, 60, 150),
                                             packBodyColour(40, 40, 45),   packBodyColour(230, 120, 40), packBodyColour(60, 170, 190),
                                             packBodyColour(200, 110, 150)};
constexpr std::array<std::uint32_t, 8> kBottom{packBodyColour(40, 50, 90),   packBodyColour(30, 30, 32),  packBodyColour(110, 90, 60),
                                               packBodyColour(70, 110, 150), packBodyColour(140, 140, 135), packBodyColour(90, 40, 40),
                                               packBodyColour(60, 80, 50),  packBodyColour(190, 170, 130)};

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

}  // namespace

std::vector<BodyLook> generatedLooks(int count) {
    if (count < 1 || count > 240) throw std::invalid_argument("generatedLooks: count must be 1-240, got " + std::to_string(count));
    std::vector<BodyLook> looks;
    // Clothes change fastest (they are most of the figure), skin and hair on other strides: the
    // first ten differ in their tops, and no two of the 240 are alike.
    for (int j = 0; j < count; ++j) {
        const auto u = static_cast<std::size_t>(j);
        looks.push_back(BodyLook{{kSkin[(u * 5 + 2) % kSkin.size()], kHair[(u / 2 + u) % kHair.size()], kTop[u % kTop.size()],
                                  kBottom[(u * 3 + u / 10) % kBottom.size()]}});
    }
    return looks;
}

const BodyLook& lookForActor(const std::vector<BodyLook>& looks, std::size_t group, std::size_t index) {
    if (looks.empty()) throw std::invalid_argument("lookForActor: no looks to choose from");
    return looks[mix(mix(group) ^ index) % looks.size()];
}

std::uint32_t parseBodyColour(const std::string& text) {
    const auto hex = [&](std::size_t i) {
        const int c = std::tolower(static_cast<unsigned char>(text[i]));
        return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    };
    bool ok = text.size() == 7 && text[0] == '#';
    for (std::size_t i = 1; ok && i < 7; ++i) ok = hex(i) >= 0;
    if (!ok) throw std::invalid_argument("'" + text + "' is not a colour \"#rrggbb\"");
    const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(hex(i) * 16 + hex(i + 1)); };
    return packBodyColour(byte(1), byte(3), byte(5));
}

}  // namespace throng::sim
