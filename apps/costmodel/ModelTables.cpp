#include "ModelTables.h"

#include <cmath>

namespace throng::costmodel {

TextTable table5(const CostModel& model) {
    const OperationCounts t = model.traditionalCounts(), a = model.actorCounts(), p = CostModel::publishedActorCounts();
    const bool example = model.factors().isExampleScene();
    TextTable table({"Notation", "Traditional processing", "Actor processing", "Trad", "Actor", example ? "Actor (printed)" : ""});
    auto row = [&](const char* name, const char* trad, const char* act, double tv, double av, double pv) {
        const bool whole = std::abs(av - std::round(av)) < 1e-9;
        table.addRow({name, trad, act, grouped(tv), whole ? grouped(av) : fixed(av, 2), example ? grouped(pv) : ""});
    };
    row("NO_01", "nActors x nSkelsPerActor", "(fSklsrootBsphsIn x nActors) x (nSkelsPerActor x fLODtopo)", t.no01, a.no01, p.no01);
    row("NO_02", "nActors", "nActors", t.no02, a.no02, p.no02);
    row("NO_03", "nActors", "nActors x fRefpointBsphsIn", t.no03, a.no03, p.no03);
    row("NO_04a", "nActors x (1 + 1 + nBsphsPerActor)", "nActors x fCheckIntBsphs x nBsphsPerActor", t.no04a, a.no04a, p.no04a);
    row("NO_04b", "nActors x (1 + fSklsrootBsphsOut + fSklsrootBsphsIn + fSklsrootBsphsIsect x nBsphsPerActor/2)",
        "nActors x (1 + fSklsrootBsphsOut + fSklsrootBsphsIn + fCheckIntBsphs x nBsphsPerActor/2)", t.no04b, a.no04b, p.no04b);
    row("NO_05", "nActors x (1 + nSkelsPerActor)", "nActors", t.no05, a.no05, p.no05);
    return table;
}

TextTable table6() {
    TextTable table({"Notation", "Traditional processing", "Actor processing"});
    table.addRow({"CO_01a", "AverageCost", "AverageCost/2"});
    table.addRow({"CO_01b", "908", "fTrack x fCoh x 29 + fTrack x 53 + fCoh x 19 + 10"});
    table.addRow({"CO_02a", "AverageCost", "AverageCost"});
    table.addRow({"CO_02b", "454", "fCoh x 22 + 63"});
    table.addRow({"CO_03a", "AverageCost", "AverageCost/2"});
    table.addRow({"CO_03b", "566", "fCoh x 85 + 63"});
    table.addRow({"CO_04a", "50", "50"});
    table.addRow({"CO_04b", "64", "64"});
    table.addRow({"CO_05", "8", "8"});
    return table;
}

std::vector<std::string> expressions(const CostModel& model) {
    const OperationCounts t = model.traditionalCounts(), a = model.actorCounts();
    // BMC is linear in AverageCost; SGMC of actor processing is bilinear in fTrack and fCoh.
    const double bmcTrad = CostModel::behaviouralCost(t, CostModel::traditionalCosts(1.0));
    const double bmcAct = CostModel::behaviouralCost(a, CostModel::actorCosts(1.0, 0, 0));
    const double sgmcTrad = CostModel::sceneGraphCost(t, CostModel::traditionalCosts(0.0));
    auto sg = [&](double ft, double fc) { return CostModel::sceneGraphCost(a, CostModel::actorCosts(0.0, ft, fc)); };
    const double c0 = sg(0, 0), cT = sg(1, 0) - c0, cC = sg(0, 1) - c0, cTC = sg(1, 1) - c0 - cT - cC;
    std::vector<std::string> e;
    e.push_back("Trad_ProcBMC = " + grouped(bmcTrad) + " x AverageCost");
    e.push_back("Act_ProcBMC = " + grouped(bmcAct) + " x AverageCost");
    e.push_back("Trad_ProcSGMC = " + grouped(sgmcTrad));
    e.push_back("Act_ProcSGMC = " + grouped(cTC) + " x fTrack x fCoh + " + grouped(cT) + " x fTrack + " + grouped(cC) +
                " x fCoh + " + grouped(c0) + "   (recomputed from Tables 5 and 6)");
    if (model.factors().isExampleScene())
        e.push_back("Act_ProcSGMC = 11,600 x fTrack x fCoh + 21,200 x fTrack + 12,350 x fCoh + 35,290   (as published)");
    e.push_back("GlobalCostTrad_Proc = " + grouped(bmcTrad) + " x AverageCost + " + grouped(sgmcTrad));
    e.push_back("GlobalCostAct_Proc = " + grouped(bmcAct) + " x AverageCost + Act_ProcSGMC");
    e.push_back("GlobalImprovementFactor (Eq. 3) = (" + grouped(bmcTrad) + " x AverageCost + " + grouped(sgmcTrad) + ") / (" +
                grouped(bmcAct) + " x AverageCost + Act_ProcSGMC); limit for large AverageCost " +
                fixed(model.largeCostLimit(), 2));
    return e;
}

std::vector<Fig6Point> fig6(const CostModel& model, double step) {
    std::vector<Fig6Point> points;
    for (double ft : {0.0, 0.5, 1.0})
        for (double fc : {0.0, 0.5, 1.0})
            for (double ac = 0.0; ac <= 1000.0 + 1e-9; ac += step)
                points.push_back(Fig6Point{ft, fc, ac, CostModel::publishedImprovementFactor(ac, ft, fc),
                                           model.improvementFactor(ac, ft, fc)});
    return points;
}

TextTable fig6Summary(const CostModel& model) {
    TextTable table({"fTrack", "fCoh", "AC = 0", "AC = 100", "AC = 1000", "AC -> inf", "AC = 0 (recomputed)"});
    for (double ft : {0.0, 0.5, 1.0})
        for (double fc : {0.0, 0.5, 1.0})
            table.addRow({fixed(ft, 1), fixed(fc, 1), fixed(CostModel::publishedImprovementFactor(0, ft, fc), 2),
                          fixed(CostModel::publishedImprovementFactor(100, ft, fc), 2),
                          fixed(CostModel::publishedImprovementFactor(1000, ft, fc), 2), fixed(model.largeCostLimit(), 2),
                          fixed(model.improvementFactor(0, ft, fc), 2)});
    return table;
}

}  // namespace throng::costmodel
