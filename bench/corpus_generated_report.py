"""docs/corpus_generated.md from the results of tests/corpus/run.py --pif --json."""
import collections
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "corpus"))
from run import invariant  # noqa: E402


VARIATION_NAMES = {"clean": "clean", "noise0.25": "0.25% noise of the diagonal", "noise0.5": "0.5% noise of the diagonal",
                   "density3": "density varying 3:1", "density5": "density varying 5:1", "missing": "missing patches"}


def failures(case, side):
    """run.py's invariants, for either side (run.py records ours only)."""
    return invariant({"kind": case["kind"], "components": case["components"]}, case["variation"], case[side])


def holds(case, side):
    return not failures(case, side)


def cell(case, side):
    r = case[side]
    if r["exit"] != 0:
        return f"exit {r['exit']}", "", "", "no"
    f = failures(case, side)
    return f"{r['hausdorff_U']:.2f}", f"{r['mean_U']:.3f}", str(r["facets"]), "yes" if not f else ", ".join(f)


def main():
    results_path, doc, command = sys.argv[1:4]
    with open(results_path) as f:
        cases = json.load(f)
    for c in cases:
        c["ours_failed"] = c["failed"]
    lines = ["# Generated corpus: invariants and accuracy, ours against PIF", "",
             f"Made by `{command}` (tests/corpus/generate.py, run.py). Each model is sampled with 50,000 points "
             f"({', '.join(sorted({VARIATION_NAMES.get(c['variation'], c['variation']) for c in cases}))}), reconstructed at delta 5 by `reconstruct` "
             "(ours) and `reconstruct --no-features` (PIF), and measured against its generating mesh. U is the "
             "average spacing of the clean sample. *Valid* is the invariant: a closed solid comes out closed "
             "(except with missing patches), with its component count (ours); an open sheet comes out open with "
             "no surface beyond the trim distance; always manifold, no self-intersection.", ""]
    # Per family.
    lines += ["## Per family", "", "| family | kind | cases | ours valid | PIF valid | ours Hausdorff below PIF's | median Hausdorff ours / PIF (U) |",
              "|---|---|---|---|---|---|---|"]
    families = collections.defaultdict(list)
    for c in cases:
        families[c["family"]].append(c)
    for family, group in sorted(families.items()):
        both = [c for c in group if c["ours"]["exit"] == 0 and c["pif"]["exit"] == 0]
        better = sum(c["ours"]["hausdorff_U"] < c["pif"]["hausdorff_U"] for c in both)
        med = lambda side: statistics.median(c[side]["hausdorff_U"] for c in both) if both else float("nan")
        lines.append(f"| {family} | {group[0]['kind']} | {len(group)} | {sum(not c['ours_failed'] for c in group)} | "
                     f"{sum(holds(c, 'pif') for c in group)} | {better} of {len(both)} | {med('ours'):.2f} / {med('pif'):.2f} |")
    total = len(cases)
    lines += ["", f"All: ours valid in {sum(not c['ours_failed'] for c in cases)} of {total} cases, "
              f"PIF in {sum(holds(c, 'pif') for c in cases)}.", ""]
    # Thickness curve.
    lines += ["## Validity by thickness", "",
              "Closed solids by their thinnest part (wall, bar, slot or gap, in average spacings of the clean "
              "sample), every variation but missing patches.", "",
              "| thinnest part (spacings) | cases | ours valid | PIF valid |", "|---|---|---|---|"]
    bins = [(0, 2), (2, 3), (3, 4), (4, 6), (6, 10), (10, 1e9)]
    for lo, hi in bins:
        group = [c for c in cases if c["kind"] == "closed" and c["variation"] != "missing" and c["thin"] is not None
                 and lo <= c["thin"] < hi]
        if group:
            label = f"{lo}-{hi}" if hi < 1e9 else f"{lo} and more"
            lines.append(f"| {label} | {len(group)} | {sum(not c['ours_failed'] for c in group)} | {sum(holds(c, 'pif') for c in group)} |")
    # Every case.
    lines += ["", "## Every case", "",
              "| model | variation | thinnest (U) | ours Hausdorff (U) | ours mean (U) | ours facets | ours valid | PIF Hausdorff (U) | PIF mean (U) | PIF facets | PIF valid |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        o, p = cell(c, "ours"), cell(c, "pif")
        ov = "yes" if not c["ours_failed"] else ", ".join(c["ours_failed"])
        thin = f"{c['thin']:.1f}" if c["thin"] is not None else "open"
        lines.append(f"| {c['model']} | {c['variation']} | {thin} | {o[0]} | {o[1]} | {o[2]} | {ov} | {p[0]} | {p[1]} | {p[2]} | {p[3]} |")
    with open(doc, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
