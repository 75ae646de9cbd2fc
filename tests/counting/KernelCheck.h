#pragma once
// Compares a kernel's hand-written tally with the operations it executed on counting values.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "CountedScalar.h"
#include "throng/scenegraph/OpCounter.h"

namespace throng::counting {

/// "m mults, a adds, d divs, s sqrts".
inline std::string describe(const OpTally& t) {
    std::ostringstream out;
    out << t.mults << " mults, " << t.adds << " adds, " << t.divs << " divs, " << t.sqrts << " sqrts (" << t.fmult()
        << " FMULT)";
    return out.str();
}

/// Runs `kernel(OpTally* hand)`, which must call a kernel instantiated on counting values with
/// `hand` as its tally, and checks that the hand-written tally equals the operations executed.
/// Returns the executed tally.
template <class Kernel>
OpTally expectTallyMatchesExecuted(const std::string& what, Kernel&& kernel) {
    OpTally hand;
    const OpTally executed = executedBy([&] { kernel(&hand); });
    EXPECT_EQ(hand, executed) << what << ": hand-written tally " << describe(hand) << ", executed " << describe(executed);
    return executed;
}

}  // namespace throng::counting

/// Skips a test when counting is compiled out (THRONG_TALLY then records nothing).
#define THRONG_SKIP_WITHOUT_COUNTING()                                                 \
    do {                                                                             \
        if (!::throng::OpCounter::compiledIn()) GTEST_SKIP() << "counting compiled out"; \
    } while (0)
