#!/usr/bin/env python3
"""Per-world means of daep-benchmark results beside the reference runs (REFERENCE.md, section 7).

usage: scripts/reference_table.py DIR [DIR ...]

Reads DIR/results.csv of one or more benchmark output folders (for example one per seed) and
prints a markdown table: per world and planner the mean over all ok runs of coverage (C %),
coverage as a share of the reachable bound, exploration time (T s), collisions per run (NOC)
and static collisions, next to the authors' own runs of the paper's Table I, and the mean over
worlds at the bottom. Python 3, standard library only.
"""
import csv
import sys
from collections import defaultdict

# The authors' runs (C %, T s, NOC per run), dynamic worlds: REFERENCE.md, section 7.
REFERENCE = {
    "daep": {
        "cafe": (92.1, 316, 0.0), "maze": (85.5, 612, 0.2), "apartment": (87.8, 1174, 1.2),
        "tunnel": (92.8, 397, 0.0), "field": (90.5, 1200, 0.8), "auditorium": (92.4, 552, 0.0),
        "exhibition": (92.4, 287, 0.0), "crosswalks": (93.4, 260, 0.6),
        "patrol": (94.6, 508, 0.0)},
    "aep": {
        "cafe": (87.8, 158, 1.6), "maze": (60.4, 292, 4.2), "apartment": (81.8, 843, 8.2),
        "tunnel": (90.8, 207, 0.2), "field": (77.4, 1010, 8.0), "auditorium": (83.6, 267, 2.2),
        "exhibition": (89.2, 132, 0.2), "crosswalks": (90.7, 133, 3.2),
        "patrol": (90.4, 289, 2.4)},
    "dep": {
        "cafe": (90.1, 496, 3.8), "maze": (50.3, 677, 10.4), "apartment": (47.7, 848, 8.2),
        "tunnel": (93.7, 999, 2.4), "field": (91.1, 1194, 7.0), "auditorium": (88.0, 678, 1.8),
        "exhibition": (94.0, 434, 4.4), "crosswalks": (92.0, 578, 7.0),
        "patrol": (95.2, 1071, 12.4)},
}
WORLDS = ["cafe", "maze", "apartment", "tunnel", "field", "auditorium", "exhibition",
          "crosswalks", "patrol"]


def mean(values):
    return sum(values) / len(values) if values else float("nan")


def read_runs(folders):
    runs = defaultdict(list)  # (planner, world) -> rows
    for folder in folders:
        with open(folder.rstrip("/") + "/results.csv", newline="") as f:
            for row in csv.DictReader(f):
                if row["status"] == "ok" and row["mode"] == "dynamic":
                    runs[(row["planner"], row["world"])].append(row)
    return runs


def main(folders):
    runs = read_runs(folders)
    planners = [p for p in ("aep", "dep", "daep") if any(k[0] == p for k in runs)]
    print("| world | planner | runs | C % | reference C % | C / reachable % | T s | reference T s"
          " | NOC | reference NOC | static |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    summary = defaultdict(lambda: defaultdict(list))
    for world in WORLDS:
        for planner in planners:
            rows = runs.get((planner, world), [])
            if not rows:
                continue
            c = mean([float(r["coverage_percent"]) for r in rows])
            share = mean([100 * float(r["coverage_percent"]) / float(r["reachable_percent"])
                          for r in rows if r["reachable_percent"]])
            t = mean([float(r["exploration_time_s"]) for r in rows])
            noc = mean([float(r["collisions"]) for r in rows])
            static = sum(int(r["static_collisions"]) for r in rows)
            rc, rt, rn = REFERENCE[planner][world]
            mark = "" if c >= rc else " (below)"
            print(f"| {world} | {planner.upper()} | {len(rows)} | {c:.2f}{mark} | {rc} | "
                  f"{share:.1f} | {t:.0f} | {rt} | {noc:.2f} | {rn} | {static} |")
            for key, value in (("c", c), ("rc", rc), ("t", t), ("rt", rt), ("noc", noc),
                               ("rn", rn), ("static", static)):
                summary[planner][key].append(value)
    for planner in planners:
        s = summary[planner]
        print(f"| mean over {len(s['c'])} worlds | {planner.upper()} | | {mean(s['c']):.2f} | "
              f"{mean(s['rc']):.2f} | | {mean(s['t']):.0f} | {mean(s['rt']):.0f} | "
              f"{mean(s['noc']):.2f} | {mean(s['rn']):.2f} | {sum(s['static'])} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip().splitlines()[2])
    main(sys.argv[1:])
