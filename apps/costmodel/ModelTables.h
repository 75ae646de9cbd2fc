#pragma once
// The cost model's tables as printed by the paper (Tables 5 and 6, the BMC / SGMC / GlobalCost
// expressions, Eq. 3) and Fig. 6's data, computed from a CostModel.

#include <string>
#include <vector>

#include "TextTable.h"
#include "throng/research/CostModel.h"

namespace throng::costmodel {

/// One point of Fig. 6.
struct Fig6Point {
    double fTrack = 0, fCoh = 0, averageCost = 0;
    double factor = 0;            ///< Eq. 3 as published
    double recomputedFactor = 0;  ///< Eq. 3 from Tables 5 (formulas) and 6
};

/// Table 5: qualitative formulas and values, both methods (and the printed actor value).
TextTable table5(const CostModel& model);
/// Table 6: cost of each operation.
TextTable table6();
/// BMC, SGMC, GlobalCost and Eq. 3 for the model's factors, one line each.
std::vector<std::string> expressions(const CostModel& model);
/// Fig. 6: AverageCost from 0 to 1000 FMULT in steps of `step`, for (fTrack, fCoh) in {0, 0.5, 1}^2.
std::vector<Fig6Point> fig6(const CostModel& model, double step = 10.0);
/// A few values of Fig. 6 (AverageCost 0, 100, 1000 and the limit) as a table.
TextTable fig6Summary(const CostModel& model);

}  // namespace throng::costmodel
