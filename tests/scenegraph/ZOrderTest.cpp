// zOrder: keys of cells near each other are near each other, and no point breaks it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "throng/scenegraph/ZOrder.h"

using namespace throng;

// The four cells of an aligned 2 x 2 square get four consecutive keys, and the sixteen of a 4 x 4
// square sixteen: a Z curve visits a square before leaving it.
TEST(ZOrder, AnAlignedSquareOfCellsHasConsecutiveKeys) {
    for (int size : {2, 4}) {
        std::set<std::uint64_t> keys;
        for (int i = 0; i < size; ++i)
            for (int j = 0; j < size; ++j) keys.insert(zOrder(16.0 * (8 + i) + 3.0, 16.0 * (-8 + j) + 5.0, 16.0));
        ASSERT_EQ(keys.size(), std::size_t(size * size)) << "one key per cell";
        EXPECT_EQ(*keys.rbegin() - *keys.begin(), std::uint64_t(size * size - 1)) << size << " x " << size;
    }
    EXPECT_EQ(zOrder(0.5, 0.5, 16.0), zOrder(15.5, 15.5, 16.0)) << "one cell, one key";
    EXPECT_NE(zOrder(-0.5, 0.5, 16.0), zOrder(0.5, 0.5, 16.0)) << "either side of the origin";
}

// Ground beyond the curve's reach shares its last cell's key; a NaN or an infinity gives a key too.
TEST(ZOrder, FarAndNonFinitePointsGetAKey) {
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(zOrder(1e300, 0.0, 1.0), zOrder(inf, 0.0, 1.0));
    EXPECT_EQ(zOrder(-1e300, 0.0, 1.0), zOrder(-inf, 0.0, 1.0));
    EXPECT_LT(zOrder(-inf, -inf, 1.0), zOrder(inf, inf, 1.0));
    EXPECT_EQ(zOrder(std::nan(""), 0.0, 1.0), zOrder(0.0, 0.0, 1.0)) << "a NaN counts as the origin's cell";
}
