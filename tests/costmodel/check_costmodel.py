#!/usr/bin/env python3
"""Checks throng-costmodel's JSON output: the keys the report promises, Table 5, Fig. 6 values, the
measured Table 2 classification (from the pipeline's own counters) and the errata.

usage: check_costmodel.py JSON_FILE"""
import json
import sys


def main():
    data = json.load(open(sys.argv[1]))
    errors = []

    def expect(cond, what):
        if not cond:
            errors.append(what)

    keys = ["NO_01", "NO_02", "NO_03", "NO_04a", "NO_04b", "NO_05"]
    for method in ("trad", "act"):
        expect(set(keys) <= set(data["model"][method]), f"model.{method} lacks a category")
        expect(set(keys) <= set(data["measured"][method]), f"measured.{method} lacks a category")
    expect(data["model"]["trad"]["NO_01"] == 4000 and data["model"]["act"]["NO_01"] == 400, "Table 5 NO_01")
    expect(data["model"]["trad"]["NO_04a"] == 8200 and data["model"]["act"]["NO_04a"] == 160, "Table 5 NO_04a")
    fig6 = {(p["fTrack"], p["fCoh"], p["AverageCost"]): p["factor"] for p in data["fig6"]}
    expect(abs(fig6[(0.0, 0.0, 0.0)] - 119.19) < 0.005, "Fig. 6 at (0, 0, 0)")
    expect(abs(fig6[(1.0, 1.0, 0.0)] - 52.29) < 0.005, "Fig. 6 at (1, 1, 0)")
    expect(len(fig6) == 9 * 11, "Fig. 6 has 9 curves of 11 points")
    c = data["measured"]["classification"]
    expect((c["A"], c["B"], c["C1"], c["C2"], c["C3_1"], c["C3_2"]) == (20, 30, 20, 20, 8, 2),
           f"Table 2 classification, got {c}")
    expect(data["measured"]["trad"]["NO_01"] == 4000, "measured traditional NO_01")
    expect(data["measured"]["act"]["NO_02"] == 100, "measured actor NO_02")
    errata = " ".join(data["errata"])
    expect("220" in errata and "23,100" in errata and "22880" in errata, "errata numbers")
    if errors:
        sys.exit("check_costmodel: " + "; ".join(errors))
    print("check_costmodel: all checks passed")


if __name__ == "__main__":
    main()
