#!/usr/bin/env python3
"""Checks throng-costmodel's JSON output: the keys the report promises, Table 5, Fig. 6 values, the
measured Table 2 classification (from the pipeline's own counters), the errata, and, category by
category, the FMULT the pipeline counted against what its kernels predict.

The prediction: throng-costmodel reports the cost of one invocation of each counted kernel on the
example scene's data (from the kernels' own tallies, which test_counted_ops checks against the
operations the kernels execute on an operation-counting number type) and how many invocations the
cascade calls for (from the scene and the frame's statistics, never from the counters). This script
multiplies them. Categories whose work is fixed by the scene's structure must match exactly; the two
sphere categories depend on what each merge and test finds, so their elementary operations are
decomposed into the kernels' invocations, which must come out whole and within the structure's bounds.

Then each category is set beside the paper's model (Tables 5 and 6 at the measured AverageCost,
fTrack = fCoh = 1), and every difference must have a stated direction and reason below (WHY), whose
direction is checked against the numbers.

usage: check_costmodel.py JSON_FILE"""
import json
import sys

CATEGORIES = ["NO_01", "NO_02", "NO_03", "NO_04a", "NO_04b", "NO_05"]
# Counter categories of each NO_xx: the matrix part, then the DOF values (CO_xxa), as OpCategory.
PARTS = {"NO_01": ("NO_01", "CO_01a"), "NO_02": ("NO_02", "CO_02a"), "NO_03": ("NO_03", "CO_03a"),
         "NO_04a": ("NO_04a",), "NO_04b": ("NO_04b",), "NO_05": ("NO_05",)}

# Where Throng's pipeline does more (or less) than the paper's model, and why. Direction is the
# sign of measured - model in FMULT; the script fails if a category differs from the model in a
# direction not explained here.
WHY = {
    ("trad", "NO_01"): ("less",
        "Traditional processing evaluates every Skeleton node as the model says (4,000), but a node costs "
        "what Throng's code does: its local matrix from two axis rotations (clamp, half angle, sine and "
        "cosine priced as square roots, quaternion product, rotation matrix), one float affine product with "
        "its parent and one double affine product into the world, plus the key-frame sampling of its two "
        "channels (CO_01a). The model charges 908 FMULT per node for the matrix alone (CO_01b)."),
    ("act", "NO_01"): ("more",
        "Actor processing poses every actor that passes CULL 2 (B, C2 and C3), not only C2 as Table 5 "
        "does, with half of the nodes active, and composes every drawn node's world matrix on the CPU (an "
        "affine product per drawn node); the model leaves those products to graphics hardware at 10 FMULT "
        "(fTrack = 1 charges 10 + 53 + 19 + 29 per node)."),
    ("trad", "NO_02"): ("less",
        "The Reference Point's matrix comes from the behaviour (a standing actor: one comparison, a sine and "
        "a cosine, CO_02a) and the actors hang under the scene root, whose world matrix is the identity, so "
        "no product is made; the model charges 454 FMULT per actor for the matrix."),
    ("act", "NO_02"): ("less",
        "As for traditional processing: the behaviour's sine and cosine, no product under the identity "
        "root; the model charges 22 + 63 per actor for the matrix (fCoh = 1) besides AverageCost."),
    ("trad", "NO_03"): ("less",
        "The Skeleton Root's matrix is one rotation-to-matrix (33 FMULT) and one affine product (63), and "
        "its DOF values are the clip's root channel; the model charges 566 per actor besides AverageCost."),
    ("act", "NO_03"): ("more",
        "Actor processing places the Skeleton Root of every actor that passes CULL 1 (B + C = 80, section "
        "4.2), where Table 5 counts B only (30); each costs the root channel, 33 and 63 FMULT, less than the "
        "model's 85 + 63 + AverageCost / 2."),
    ("trad", "NO_04a"): ("more",
        "Every internal sphere is placed in the world (a transform of 70 FMULT with the spectral-norm bound "
        "and the rounding pad) and merged into its parent's (up to 41 FMULT), and CULL places each drawn "
        "part's sphere too; the model charges 50 per sphere."),
    ("act", "NO_04a"): ("more",
        "Actor processing places the 100 Refpoint Bspheres in the world (the model counts none) and "
        "computes the internal spheres of every C3 actor, because the internal bound tells C3.1 from C3.2; "
        "the model counts C3.2 only. Each sphere costs what the transform and merge kernels do."),
    ("trad", "NO_04b"): ("less",
        "Plane masks: a sphere inside a plane is not tested against it again below it, a sphere inside "
        "every plane ends the tests of its subtree, and a test stops at the first plane the sphere is "
        "outside of; each plane costs 8 FMULT (the model: 64 per test)."),
    ("act", "NO_04b"): ("less",
        "The same plane masks and early outs; CULL 2 tests only actors whose Refpoint Bsphere crosses a plane "
        "(the model: 64 FMULT for every test)."),
    ("trad", "NO_05"): ("more",
        "Only the LOD nodes CULL reaches compute their distance (fewer than the model's 41 per actor), but "
        "each computes the detail distance with the LOD scale and the priority: 15 FMULT (a division), "
        "not 8."),
    ("act", "NO_05"): ("more",
        "One distance per actor that passes CULL 2 (60, not 100), but each is computed twice: the squared "
        "detail distance with scale and priority (15 FMULT) and the eye distance kept for the actor (15, "
        "with its square root); the model charges 8."),
}

# Work the pipeline does that no counter sees (it is in no counted kernel): the predictions below
# leave it out as the counters do, and the report names it.
UNCOUNTED = [
    "the clip time (time x timeScale + timeOffset) KeyframeBehaviour computes before each sample",
    "skeletal LOD (computeActiveNodes: a square and a comparison per node) and the behavioural level "
    "(a square root and comparisons per actor)",
    "choosing a vaLod level (a comparison per range) in both methods",
    "the merge of each actor's whole bound into its node's bound under traditional processing, and the "
    "tests of held objects in the draw list",
]


def main():
    data = json.load(open(sys.argv[1]))
    errors = []

    def expect(cond, what):
        if not cond:
            errors.append(what)

    keys = CATEGORIES
    for method in ("trad", "act"):
        expect(set(keys) <= set(data["model"][method]), f"model.{method} lacks a category")
        expect(set(keys) <= set(data["measured"][method]), f"measured.{method} lacks a category")
    expect(data["model"]["trad"]["NO_01"] == 4000 and data["model"]["act"]["NO_01"] == 400, "Table 5 NO_01")
    expect(data["model"]["trad"]["NO_04a"] == 8200 and data["model"]["act"]["NO_04a"] == 160, "Table 5 NO_04a")
    fig6 = {(p["fTrack"], p["fCoh"], p["AverageCost"]): p["factor"] for p in data["fig6"]}
    expect(abs(fig6[(0.0, 0.0, 0.0)] - 119.19) < 0.005, "Fig. 6 at (0, 0, 0)")
    expect(abs(fig6[(1.0, 1.0, 0.0)] - 52.29) < 0.005, "Fig. 6 at (1, 1, 0)")
    expect(len(fig6) == 9 * 11, "Fig. 6 has 9 curves of 11 points")
    m = data["measured"]
    c = m["classification"]
    expect((c["A"], c["B"], c["C1"], c["C2"], c["C3_1"], c["C3_2"]) == (20, 30, 20, 20, 8, 2),
           f"Table 2 classification, got {c}")
    expect(m["trad"]["NO_01"] == 4000, "measured traditional NO_01")
    expect(m["act"]["NO_02"] == 100, "measured actor NO_02")
    errata = " ".join(data["errata"])
    expect("220" in errata and "23,100" in errata and "22880" in errata, "errata numbers")

    predicted = check_against_kernels(m, expect)
    check_against_model(m, predicted, expect)
    if errors:
        sys.exit("check_costmodel: " + "; ".join(errors))
    print("check_costmodel: all checks passed")


def check_against_kernels(m, expect):
    """FMULT per counter category predicted by the kernels; exact where the structure fixes the work."""
    k = {name: t["fmult"] for name, t in m["kernels"].items()}
    ops = m["kernels"]
    counters = m["counters"]
    predicted = {}
    for method in ("trad", "act"):
        s = m["structure"][method]
        p = {}
        if method == "trad":
            n, nodes, roots = s["actors"], s["nodesPerActor"], s["rootNodesPerActor"]
            # Every actor at level 0: the whole clip, every node's local matrix, its product with the
            # parent and with the Skeleton Root's world matrix.
            p["CO_01a"] = n * (k["clipLocalTime"] + s["keySearchesPerActor"] * k["clipKeySearch"]
                               + s["channelsPerActor"] * k["clipChannel"])
            p["NO_01"] = n * (nodes * k["nodeLocalTransform"] + (nodes - roots) * k["compose"] + nodes * k["composeAffine"])
            p["CO_03a"] = n * k["clipRoot"]
            p["NO_05"] = s["lodDistances"] * k["detailDistanceSquared"]
        else:
            n = s["actors"]
            posed = [s[f"posedAtLevel{level}"] for level in range(3)]
            channels = [s[f"channelsAtLevel{level}"] for level in range(3)]
            searches = [s[f"keySearchesAtLevel{level}"] for level in range(3)]
            # Level 0 samples every active channel, level 1 holds keys, beyond the last band the rest
            # pose is copied (no arithmetic). Channels sharing key times share one key search.
            p["CO_01a"] = ((posed[0] + posed[1]) * k["clipLocalTime"] + (searches[0] + searches[1]) * k["clipKeySearch"]
                           + channels[0] * k["clipChannel"] + channels[1] * k["clipChannelHeld"])
            p["NO_01"] = (s["posedNodes"] * k["nodeLocalTransform"] + (s["posedNodes"] - s["posedRootNodes"]) * k["compose"]
                          + s["nodeDrawItems"] * k["composeAffine"])
            survivors = [s[f"survivorsAtLevel{level}"] for level in range(3)]
            p["CO_03a"] = survivors[0] * k["clipRoot"] + survivors[1] * k["clipRootHeld"]
            n_roots = sum(survivors)
            p["NO_05"] = s["lodDistances"] * (k["detailDistanceSquared"] + k["eyeDistance"])
        # Reference Points: every actor, whatever the method; under the identity root, no product.
        p["CO_02a"] = n * k["refpointPath"]
        p["NO_02"] = 0
        roots_placed = n if method == "trad" else n_roots
        p["NO_03"] = roots_placed * (k["rootPoseMatrix"] + k["composeAffine"])
        for cat, value in p.items():
            got = counters[method][cat]["fmult"]
            expect(got == value, f"{method} {cat}: the pipeline counted {got} FMULT, its kernels predict {value:g}")
        spheres(method, counters[method]["NO_04a"], ops, s, expect)
        frustum_tests(method, counters[method]["NO_04b"], m[method]["NO_04b"], ops, s, expect)
        predicted[method] = {cat: sum(p[part] for part in PARTS[cat] if part in p) for cat in ("NO_01", "NO_02", "NO_03", "NO_05")}
    return predicted


def spheres(method, got, ops, s, expect):
    """NO_04a is sphere transforms and merges. Each transform and each non-empty merge takes one square
    root, each full merge one division, and the transform is the one with many multiplications: the
    counted multiplications must split into whole numbers of each."""
    t, full, contained, inside = (ops[x] for x in ("sphereTransform", "sphereMergeFull", "sphereMergeContained", "sphereMergeInsideOther"))
    expect(t["sqrts"] == full["sqrts"] == contained["sqrts"] == inside["sqrts"] == 1 and full["divs"] == 1
           and t["divs"] == contained["divs"] == inside["divs"] == 0 and contained["mults"] == inside["mults"],
           "sphere kernels: the decomposition below assumes one root each and one division per full merge")
    roots, divs, mults, adds = got["sqrts"], got["divs"], got["mults"], got["adds"]
    # mults = T t.m + F full.m + (roots - T - F) contained.m, with F = divs.
    numerator = mults - full["mults"] * divs - contained["mults"] * (roots - divs)
    per = t["mults"] - contained["mults"]
    transforms = numerator // per
    expect(numerator % per == 0 and 0 <= transforms <= roots - divs,
           f"{method} NO_04a: {mults} mults, {roots} roots, {divs} divisions do not split into whole sphere transforms and merges")
    merges = roots - transforms
    expect(transforms >= s["sphereTransformsAtLeast"],
           f"{method} NO_04a: {transforms} sphere transforms counted, the cascade places at least {s['sphereTransformsAtLeast']:g}")
    # What is left of the additions is emptiness tests and the two extra comparisons of a sphere found
    # inside the other: never negative.
    rest = adds - (transforms * t["adds"] + divs * full["adds"] + (merges - divs) * contained["adds"])
    expect(rest >= 0, f"{method} NO_04a: {adds} adds are fewer than {transforms} transforms and {merges} merges take")
    print(f"{method} NO_04a: {transforms} sphere transforms (at least {s['sphereTransformsAtLeast']:g} expected), "
          f"{merges} merges of which {divs} full, {rest} adds of emptiness tests and spheres found inside the other")


def frustum_tests(method, got, calls, ops, s, expect):
    """NO_04b is frustum tests: per test one emptiness comparison, per plane tested 3 mults and 5 adds,
    one add less on the plane the sphere is outside of (where the test stops); flat-array spheres
    cost their fixed kernel."""
    none, passed, failed, flat = (ops[x] for x in ("classifyNoPlane", "classifyOnePlaneNotOutside", "classifyOnePlaneOutside", "flatArraySphere"))
    plane_m, plane_a, saved = passed["mults"], passed["adds"] - none["adds"], passed["adds"] - failed["adds"]
    flats = int(s.get("flatArraySpheres", 0))
    tests = calls - flats
    expect(got["divs"] == 0 and got["sqrts"] == 0, f"{method} NO_04b: frustum tests take no division or root")
    mults = got["mults"] - flats * flat["mults"]
    planes = mults // plane_m
    expect(mults % plane_m == 0 and planes <= 6 * tests,
           f"{method} NO_04b: {got['mults']} mults are not whole planes of {tests:g} tests")
    outside = (tests * none["adds"] + planes * plane_a + flats * flat["adds"] - got["adds"]) // saved
    expect(s.get("rejectedOutside", 0) <= outside <= tests,
           f"{method} NO_04b: {got['adds']} adds imply {outside:g} tests ending outside, out of {tests:g} "
           f"(at least {s.get('rejectedOutside', 0):g} rejections were seen)")
    print(f"{method} NO_04b: {tests:g} frustum tests, {planes} planes tested, {outside:g} tests ending outside a plane")


def check_against_model(m, predicted, expect):
    """Each category beside the paper's model, with the reason for every difference."""
    print(f"{'':8}{'method':7}{'model':>12}{'measured':>12}{'kernels':>12}  why they differ")
    for method in ("trad", "act"):
        for cat in CATEGORIES:
            model = m["modelFmult"][method][cat]
            got = m["fmult"][method][cat]
            kernels = predicted[method].get(cat)
            direction = "more" if got > model else "less" if got < model else "same"
            why = WHY.get((method, cat))
            if direction != "same":
                expect(why is not None, f"{method} {cat}: measured {got} differs from the model's {model:g} with no reason given")
                expect(why is None or why[0] == direction,
                       f"{method} {cat}: the pipeline does {direction} than the model, the reason given says {why and why[0]}")
            shown = f"{kernels:,.0f}" if kernels is not None else "decomposed"
            print(f"{cat:8}{method:7}{model:>12,.0f}{got:>12,}{shown:>12}  {direction}: {why[1] if why else ''}")
    print("not counted by any kernel (so neither measured nor predicted): " + "; ".join(UNCOUNTED))


if __name__ == "__main__":
    main()
