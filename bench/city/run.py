#!/usr/bin/python3
"""Runs `features` (and with --mesh, `reconstruct`) on generated city tiles
and measures them (evaluate.py).

    run.py SHARPMESH TILE_DIR WORK_DIR [--tiles a,b] [--mesh] [--extra "FLAGS"]
           [--json OUT.json]

Each tile's polylines, report and measures go to WORK_DIR; the summary
(median recall and precision, their lowest values) goes to stdout.
"""
import argparse
import glob
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(value):
    return "-" if value is None else "%.2f" % value


def run_tile(binary, las, work, extra, mesh):
    name = os.path.splitext(os.path.basename(las))[0]
    truth = os.path.splitext(las)[0] + ".npz"
    meta = json.load(open(os.path.splitext(las)[0] + ".json"))
    out = {"tile": name, "density_per_m2": meta["density_per_m2"], "noise_m": meta["noise_m"]}
    polylines = os.path.join(work, name + ".polylines.txt")
    report = os.path.join(work, name + ".features.json")
    subprocess.run([binary, "features", las, "-o", polylines, "--report", report, "-q"] + extra, check=True)
    measures = [sys.executable, os.path.join(HERE, "evaluate.py"), truth, "--polylines", polylines]
    r = json.load(open(report))
    out.update(seconds_features=r["seconds"], R_m=r["derived"]["R"]["value"], r_m=r["derived"]["r"]["value"],
               noise_m_estimated=r["derived"]["noise_estimate"]["value"], spacing_m=r["derived"]["average_spacing"]["value"])
    if mesh:
        mesh_path = os.path.join(work, name + ".mesh.ply")
        mesh_report = os.path.join(work, name + ".reconstruct.json")
        done = subprocess.run([binary, "reconstruct", las, "-o", mesh_path, "--report", mesh_report, "-q"] + extra)
        out["reconstruct_status"] = done.returncode
        if done.returncode == 0:
            measures += ["--mesh", mesh_path]
            rr = json.load(open(mesh_report))
            out.update(seconds_reconstruct=rr["seconds"], peak_memory_mib=rr.get("peak_memory_mib"))
    out.update(json.loads(subprocess.run(measures, check=True, capture_output=True, text=True).stdout))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binary")
    parser.add_argument("tiles")
    parser.add_argument("work")
    parser.add_argument("--tiles", dest="only", default="", help="tile numbers, e.g. 0,3,7")
    parser.add_argument("--mesh", action="store_true", help="also reconstruct and measure the mesh")
    parser.add_argument("--extra", default="", help="flags for both commands")
    parser.add_argument("--json")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    files = sorted(glob.glob(os.path.join(args.tiles, "city-*.las")))
    if args.only:
        wanted = {"city-%02d.las" % int(i) for i in args.only.split(",")}
        files = [f for f in files if os.path.basename(f) in wanted]
    results = []
    for las in files:
        results.append(run_tile(args.binary, las, args.work, shlex.split(args.extra), args.mesh))
        r = results[-1]
        print("%s: recall %.2f (ridges %.2f, eaves %s, parapets %s) precision %.2f polylines %d R %.2f m noise %.3f m" %
              (r["tile"], r["recall"], r["ridge_recall"], fmt(r["house_eave_recall"]), fmt(r["parapet_recall"]), r["precision"],
               r["polylines"], r["R_m"], r["noise_m_estimated"]), file=sys.stderr)
    def median(key):
        values = sorted(r[key] for r in results if r[key] is not None)
        return values[len(values) // 2], values[0]
    print("tiles %d: recall median %.3f min %.3f (ridges %.3f, house eaves %.3f, parapets %.3f); precision median %.3f min %.3f" %
          ((len(results),) + median("recall") + (median("ridge_recall")[0], median("house_eave_recall")[0], median("parapet_recall")[0])
           + median("precision")))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
