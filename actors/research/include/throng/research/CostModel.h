#pragma once
// The FMULT cost model of seed 002 (§6 and appendix): the factors of Table 4, the operation counts of
// Table 5 (traditional and actor processing), the costs of Table 6, the Behavioural and Scene Graph
// Management Costs, the Global Cost and the improvement factor of Eq. 3. The published equation
// uses a constant (23,100) that Tables 5 and 6 do not give; both the published and the recomputed
// forms are available, and errata() lists every inconsistency found, with its numbers.

#include <string>
#include <vector>

namespace throng {

/// Table 4: what determines the number of operations of a scene.
struct CostModelFactors {
    double nActors = 100;               ///< actors
    double fRefpointBsphsIn = 0.3;      ///< share with the Refpoint Bsphere inside the frustum (B)
    double fSklsrootBsphsOut = 0.2;     ///< share with the Sklsroot Bsphere outside (C1)
    double fSklsrootBsphsIn = 0.2;      ///< share with the Sklsroot Bsphere inside (C2)
    double fSklsrootBsphsIsect = 0.08;  ///< share crossing, internal spheres wholly in or out (C3.1)
    double fCheckIntBsphs = 0.02;       ///< share needing culling with internal spheres (C3.2)
    double nSkelsPerActor = 40;         ///< Skeleton nodes per actor
    double nBsphsPerActor = 80;         ///< internal bounding spheres per actor
    double fLODtopo = 0.5;              ///< share of Skeleton nodes left by skeletal LOD

    /// Whether these are the example scene's factors (Table 4), for which the paper prints values.
    bool isExampleScene() const;
};

/// Table 5: operations of each kind in one frame.
struct OperationCounts {
    /// \var no01
    /// NO_01: Skeleton nodes updated (DOF values, then matrix).
    /// \var no02
    /// NO_02: Reference Points updated (DOF values, then matrix).
    /// \var no03
    /// NO_03: Skeleton Roots updated (DOF values, then matrix).
    /// \var no04a
    /// NO_04a: bounding spheres recomputed from their descendants.
    /// \var no04b
    /// NO_04b: bounding spheres tested against the frustum.
    double no01 = 0, no02 = 0, no03 = 0, no04a = 0, no04b = 0, no05 = 0;  ///< NO_05: LOD eye distances
};

/// Table 6: FMULT cost of one operation of each kind.
struct OperationCosts {
    /// \var co01a
    /// CO_01a: a Skeleton node's DOF values (behaviour).
    /// \var co01b
    /// CO_01b: a Skeleton node's matrix.
    /// \var co02a
    /// CO_02a: a Reference Point's DOF values (behaviour).
    /// \var co02b
    /// CO_02b: a Reference Point's matrix.
    /// \var co03a
    /// CO_03a: a Skeleton Root's DOF values (behaviour).
    double co01a = 0, co01b = 0, co02a = 0, co02b = 0, co03a = 0, co03b = 0;  ///< CO_03b: Skeleton Root matrix
    /// \var co04a
    /// CO_04a: a bounding sphere recomputed from its descendants.
    /// \var co04b
    /// CO_04b: a sphere-frustum test.
    double co04a = 0, co04b = 0, co05 = 0;                                    ///< CO_05: an LOD eye distance
};

/// The model for one set of factors.
class CostModel {
public:
    /// The model of a scene with `factors` (default: the example scene of Tables 2-4).
    explicit CostModel(const CostModelFactors& factors = {});

    /// The factors.
    const CostModelFactors& factors() const { return factors_; }
    /// Table 5, traditional column, from its formulas.
    OperationCounts traditionalCounts() const;
    /// Table 5, actor column, from its formulas (NO_04b = 220 for the example scene).
    OperationCounts actorCounts() const;
    /// Table 5's actor column as printed for the example scene (NO_04b = 200).
    static OperationCounts publishedActorCounts();
    /// Table 6, traditional column.
    static OperationCosts traditionalCosts(double averageCost);
    /// Table 6, actor column.
    static OperationCosts actorCosts(double averageCost, double fTrack, double fCoh);

    /// BMC = NO_01 CO_01a + NO_02 CO_02a + NO_03 CO_03a.
    static double behaviouralCost(const OperationCounts& n, const OperationCosts& c);
    /// SGMC = NO_01 CO_01b + NO_02 CO_02b + NO_03 CO_03b + NO_04a CO_04a + NO_04b CO_04b + NO_05 CO_05.
    static double sceneGraphCost(const OperationCounts& n, const OperationCosts& c);
    /// Global cost of traditional processing (BMC + SGMC).
    double traditionalGlobalCost(double averageCost) const;
    /// Global cost of actor processing, recomputed from Tables 5 (formulas) and 6.
    double actorGlobalCost(double averageCost, double fTrack, double fCoh) const;
    /// Eq. 3 recomputed from Tables 5 (formulas) and 6.
    double improvementFactor(double averageCost, double fTrack, double fCoh) const;
    /// Eq. 3 as published for the example scene: (4200 AC + 4,206,240) / (315 AC + 11,600 fTrack fCoh
    /// + 21,200 fTrack + 12,350 fCoh + 35,290).
    static double publishedImprovementFactor(double averageCost, double fTrack, double fCoh);
    /// The limit of the improvement factor as AverageCost grows (BMC_trad / BMC_act per FMULT).
    double largeCostLimit() const;

    /// Every inconsistency found in the paper's model, with its numbers.
    static std::vector<std::string> errata();

private:
    CostModelFactors factors_;
};

}  // namespace throng
