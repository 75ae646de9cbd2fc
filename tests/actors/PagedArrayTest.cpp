// PagedArray (per-actor arrays whose unwritten elements take no memory) and the crowd's state
// deferred until an actor is first shown (Crowd::deferStateUntilShown). Residency is read from the
// kernel (mincore): what a rank posing its share of a crowd saves is pages never touched.

#include <gtest/gtest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <vector>

#include "throng/actors/PagedArray.h"
#include "throng/testkit/ActorTestScenes.h"

using namespace throng;
using namespace throng::testkit;

namespace {

// Pages of [data, data + bytes) resident in memory.
std::size_t residentPages(const void* data, std::size_t bytes) {
    const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
    const std::size_t pages = (bytes + page - 1) / page;
    std::vector<unsigned char> in(pages);
    EXPECT_EQ(::mincore(const_cast<void*>(data), pages * page, in.data()), 0) << std::strerror(errno);
    std::size_t n = 0;
    for (unsigned char c : in) n += c & 1;
    return n;
}

// Counted in small pages: where transparent huge pages are always on, one write would make 2 MiB
// resident (the saving then comes in huge pages; the tests count the small ones).
template <class T>
void smallPagesOnly(PagedArray<T>& a) {
    ::madvise(static_cast<void*>(a.data()), a.size() * sizeof(T), MADV_NOHUGEPAGE);
}

template <class T>
std::size_t residentPages(const PagedArray<T>& a) {
    return residentPages(a.data(), a.size() * sizeof(T));
}

bool isIdentity(const Mat4& m) {
    const Mat4 identity(1.0);
    return std::memcmp(&m, &identity, sizeof m) == 0;
}

}  // namespace

TEST(PagedArray, KeepsWhatIsWrittenAndReadsZeroWhereNothingWasThroughGrowthCopiesAndMoves) {
    PagedArray<double> a;
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.data(), nullptr);
    for (int i = 0; i < 1000; ++i) a.push_back(i * 0.5);
    a.appendUnwritten(3000);
    const double tail[] = {7.0, 8.0};
    a.append(tail);
    a.push_back(a[10]);  // an element of its own, while it grows
    ASSERT_EQ(a.size(), 4003u);
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(a[std::size_t(i)], i * 0.5);
    for (std::size_t i = 1000; i < 4000; ++i) ASSERT_EQ(a[i], 0.0) << i;
    EXPECT_EQ(a[4000], 7.0);
    EXPECT_EQ(a[4001], 8.0);
    EXPECT_EQ(a[4002], 5.0);
    a.appendUnwritten(1'000'000);  // moved pages: still zero, still what was written before
    EXPECT_EQ(a[999], 499.5);
    EXPECT_EQ(a[1'004'002], 0.0);

    PagedArray<double> copy(a);
    EXPECT_EQ(copy.size(), a.size());
    EXPECT_EQ(0, std::memcmp(copy.data(), a.data(), a.size() * sizeof(double)));
    copy[3] = -1.0;
    EXPECT_EQ(a[3], 1.5);
    PagedArray<double> moved(std::move(copy));
    EXPECT_EQ(moved[3], -1.0);
    EXPECT_TRUE(copy.empty());  // NOLINT(bugprone-use-after-move): a moved-from array is empty
    copy = moved;
    EXPECT_EQ(copy[3], -1.0);
    const std::span<const double> view(copy);
    EXPECT_EQ(view.size(), copy.size());
}

TEST(PagedArray, UnwrittenElementsTakeNoMemoryUntilWrittenEvenWhenTheArrayGrows) {
    PagedArray<Mat4> matrices;
    matrices.appendUnwritten(100'000);  // 12.8 MB
    smallPagesOnly(matrices);
    EXPECT_EQ(residentPages(matrices), 0u);
    for (std::size_t i = 0; i < 100'000; i += 10'000) matrices[i] = Mat4(2.0);
    EXPECT_EQ(residentPages(matrices), 10u);  // one page per element written, 1.25 MB apart
    // Growing past the capacity moves the pages (mremap), it does not copy them in.
    for (int i = 0; i < 10; ++i) matrices.appendUnwritten(100'000);
    EXPECT_EQ(residentPages(matrices), 10u);
    EXPECT_EQ(matrices[50'000][0][0], 2.0);
    EXPECT_EQ(matrices[50'001][0][0], 0.0);
    const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
    matrices.push_back(Mat4(3.0));  // one element: one page, two where it straddles
    EXPECT_LE(residentPages(matrices), 10u + 1u + std::size_t(sizeof(Mat4) > page % sizeof(Mat4)));
}

TEST(CrowdDeferredState, ActorsNotYetShownReadTheirInitialStateAndTakeNoPerFrameMemory) {
    const auto scene = makeRandomCrowd(11, 20'000, 200.0, true);
    Crowd& crowd = scene->crowd;
    EXPECT_EQ(crowd.deferredStates(), 20'000u);
    Crowd::State& s = crowd.state();
    smallPagesOnly(s.refWorld), smallPagesOnly(s.sklsWorld), smallPagesOnly(s.dofs);
    EXPECT_EQ(residentPages(s.refWorld), 0u);
    EXPECT_EQ(residentPages(s.sklsWorld), 0u);
    EXPECT_EQ(residentPages(s.dofs), 0u);
    for (ActorId id : {ActorId(0), ActorId(777), ActorId(19'999)}) {
        EXPECT_TRUE(isIdentity(crowd.referencePoint(id)));
        EXPECT_TRUE(isIdentity(crowd.skeletonRoot(id)));
        EXPECT_FALSE(crowd.refpointSphere(id).valid());
        const auto rest = crowd.templateOf(id).restDofs();
        ASSERT_EQ(crowd.dofs(id).size(), rest.size());
        EXPECT_TRUE(std::equal(rest.begin(), rest.end(), crowd.dofs(id).begin()));
    }
    // Written one by one (phase 1 writes those it visits): the same values, now in the arrays.
    for (ActorId id = 0; id < 100; ++id) crowd.writeState(id);
    crowd.writeState(50);  // twice is once
    EXPECT_EQ(crowd.deferredStates(), 19'900u);
    EXPECT_TRUE(isIdentity(s.refWorld[42]));
    const auto rest = crowd.templateOf(42).restDofs();
    EXPECT_TRUE(std::equal(rest.begin(), rest.end(), s.dofs.data() + s.dofOffset[42]));
    EXPECT_LE(residentPages(s.refWorld), 100 * sizeof(Mat4) / std::size_t(::sysconf(_SC_PAGESIZE)) + 1);
    crowd.writeAllStates();
    EXPECT_EQ(crowd.deferredStates(), 0u);
    EXPECT_TRUE(isIdentity(s.sklsWorld[19'999]));
}

TEST(CrowdDeferredState, ACrowdThatDoesNotDeferWritesEveryStateWhenActorsAreAdded) {
    const auto scene = makeRandomCrowd(11, 500, 50.0);
    EXPECT_EQ(scene->crowd.deferredStates(), 0u);
    const Crowd::State& s = scene->crowd.state();
    for (ActorId id = 0; id < 500; ++id) {
        ASSERT_TRUE(isIdentity(s.refLocal[id]));
        const auto rest = scene->crowd.templateOf(id).restDofs();
        ASSERT_TRUE(std::equal(rest.begin(), rest.end(), s.dofs.data() + s.dofOffset[id]));
    }
}
