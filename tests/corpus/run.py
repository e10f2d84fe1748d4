#!/usr/bin/python3
"""The corpus invariant suite (issue 36 item 3; libigl's run_test_cases idea).

    run.py SHARPMESH CORPUS_DIR WORK_DIR [--cases FILE | --models a,b] [--points 50000]
           [--variations clean,noise0.5,...] [--deltas 3.5,5] [--pif] [--json OUT]

For every model, sampling variation, point count and delta: sample the
reference (`sharpmesh sample`), reconstruct, evaluate against the reference,
and check the invariants:
- a closed input gives a closed, edge- and vertex-manifold mesh without
  self-intersecting facets (CGAL's exact test) and with the input's
  component count;
- an open input gives an open, manifold mesh without self-intersections
  that invents no surface: no mesh point farther from the reference than
  the reconstruction's trim distance (d' + 2 average spacings);
- a closed input with missing patches gives a manifold mesh without
  self-intersections (open or closed: the holes may be wider than the trim).
With --pif the PIF baseline (`--no-features`) runs too, for the distances.
Exits 1 when an invariant fails, and prints one line per case.
"""
import argparse
import json
import os
import subprocess
import sys

VARIATIONS = {
    "clean": [],
    "noise0.25": ["--noise", "0.0025"],
    "noise0.5": ["--noise", "0.005"],
    "density3": ["--density-ratio", "3"],
    "density5": ["--density-ratio", "5"],
    "missing": ["--missing-patches", "3", "--missing-radius", "0.06"],
}


# A case that runs longer than this counts as failed ("exit timeout"): a
# user waits minutes for a 50k-point part, not hours.
TIMEOUT_SECONDS = 900


def run(cmd, log):
    with open(log, "w") as f:
        try:
            return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=TIMEOUT_SECONDS).returncode
        except subprocess.TimeoutExpired:
            return "timeout"


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def reconstruct(binary, cloud, reference, tag, delta, extra):
    mesh, report, evaluation = tag + ".ply", tag + ".json", tag + ".eval.json"
    if not (os.path.exists(evaluation) and os.path.exists(report)):
        code = run([binary, "reconstruct", cloud, "-o", mesh, "--delta", str(delta), "--report", report, "-q", *extra], tag + ".log")
        if code != 0:
            return {"exit": code}
        if run([binary, "eval", mesh, "-r", reference, "--json", evaluation, "-q"], tag + ".eval.log") != 0:
            return {"exit": "eval failed"}
    r, e = load(report), load(evaluation)
    if r is None or e is None:
        return {"exit": "missing report"}
    e = e["evaluation"]
    t = e["topology"]
    derived = r.get("derived", {})
    # The reconstruction's trim distance at its default: d' + 2 avg.
    trim = derived["d_prime"]["value"] + 2 * derived["average_spacing"]["value"] if "d_prime" in derived else None
    return {
        "exit": 0,
        "hausdorff_U": e["hausdorff"]["U"],
        "mean_U": e["mean"]["U"],
        "mesh_to_reference_max": e["mesh_to_reference_max"]["value"],
        "facets": e["facets"],
        "closed": t["closed"],
        "boundary_edges": t["boundary_edges"],
        "manifold": t["non_manifold_edges"] == 0 and t["non_manifold_vertices"] == 0,
        "self_intersecting": t["self_intersecting"],
        "components": t["components"],
        "trim_distance": trim,
        "seconds": r.get("seconds"),
    }


def invariant(meta, variation, result):
    """The failed invariants of one case, as short words (empty: it holds)."""
    if result["exit"] != 0:
        return [f"exit {result['exit']}"]
    failed = []
    if not result["manifold"]:
        failed.append("non-manifold")
    if result["self_intersecting"]:
        failed.append("self-intersecting")
    if meta["kind"] == "closed" and variation != "missing":
        if not result["closed"]:
            failed.append(f"open ({result['boundary_edges']} boundary edges)")
        if result["components"] != meta["components"]:
            failed.append(f"{result['components']} components (input {meta['components']})")
    if meta["kind"] == "open":
        if result["closed"]:
            failed.append("closed")
        trim = result["trim_distance"]
        if trim is not None and result["mesh_to_reference_max"] > trim:
            failed.append("invented surface")
    return failed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("corpus")
    parser.add_argument("work")
    parser.add_argument("--models", default="", help="comma-separated model names (default: every model in CORPUS_DIR)")
    parser.add_argument("--points", default="50000")
    parser.add_argument("--variations", default="clean")
    parser.add_argument("--deltas", default="5")
    parser.add_argument("--seed", type=int, default=1, help="sampling seed")
    parser.add_argument("--pif", action="store_true", help="also run the PIF baseline (--no-features)")
    parser.add_argument("--extra", default="", help="more reconstruct flags for every case, e.g. '--tiles 3'")
    parser.add_argument("--json", help="write every case's result here")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    models = [m for m in args.models.split(",") if m] or sorted(f[:-5] for f in os.listdir(args.corpus) if f.endswith(".json"))
    results, failures = [], 0
    for model in models:
        meta = load(os.path.join(args.corpus, model + ".json"))
        reference = os.path.join(args.corpus, model + ".off")
        for variation in args.variations.split(","):
            if variation == "missing" and meta["kind"] == "open":
                continue
            for points in args.points.split(","):
                cloud = os.path.join(args.work, f"{model}-{variation}-{points}.xyz")
                if not os.path.exists(cloud):
                    code = run([args.binary, "sample", reference, "-n", points, "--seed", str(args.seed), "-o", cloud + ".tmp.xyz", "-q",
                                *VARIATIONS[variation]], cloud + ".log")
                    if code != 0:
                        print(f"FAIL {model} {variation} {points}: sampling failed", flush=True)
                        failures += 1
                        continue
                    os.replace(cloud + ".tmp.xyz", cloud)
                for delta in args.deltas.split(","):
                    tag = os.path.join(args.work, f"{model}-{variation}-{points}-d{delta}")
                    case = {"model": model, "family": meta["family"], "kind": meta["kind"], "variation": variation,
                            "points": int(points), "delta": float(delta), "thin": meta.get("thin"),
                            "spacing_50k": meta.get("spacing_50k"), "components": meta.get("components")}
                    case["ours"] = reconstruct(args.binary, cloud, reference, tag + "-ours", delta, args.extra.split())
                    if args.pif:
                        case["pif"] = reconstruct(args.binary, cloud, reference, tag + "-pif", delta, ["--no-features"])
                    case["failed"] = invariant(meta, variation, case["ours"])
                    results.append(case)
                    ours = case["ours"]
                    line = f"{model} {variation} {points} delta {delta}"
                    if ours["exit"] == 0:
                        line += f": {ours['hausdorff_U']:.2f} U, mean {ours['mean_U']:.3f} U, {ours['facets']} facets"
                        if args.pif and case["pif"]["exit"] == 0:
                            line += f" (PIF {case['pif']['hausdorff_U']:.2f} U, mean {case['pif']['mean_U']:.3f} U)"
                    if case["failed"]:
                        failures += 1
                        print(f"FAIL {line}: {', '.join(case['failed'])}", flush=True)
                    else:
                        print(f"ok   {line}", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    print(f"corpus: {len(results) - failures} of {len(results)} cases hold their invariants", flush=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
