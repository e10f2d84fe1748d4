"""docs/scale.{md,png} from bench/scale's summary: time and the kernel's peak
memory against the point count, per stage, with the peers of the same run."""
import json, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

summary, docs = json.load(open(sys.argv[1])), sys.argv[2]
rows, tiles = summary["fandisk"], summary["lidar"]
stage_groups = [("features", ("spacing", "detection", "clustering", "polylines", "junctions")),
                ("normals", ("normals", "normals (fallback)")), ("Poisson", ("poisson", "poisson (fallback)", "sign repair")),
                ("meshing", ("restriction", "seeds", "refinement", "flattening", "trim", "data fit", "snapping",
                             "data fit after snapping", "self-intersection check"))]


def grouped(stages):
    return {label: sum(stages.get(name, 0) for name in names) for label, names in stage_groups}


def fmt(value, digits=1):
    return "—" if value is None else f"{value:,.{digits}f}"


lines = ["# Scale on one machine", "",
         "Produced by `bench/scale` (issue 38): `sharpmesh reconstruct` with defaults on fandisk sampled uniformly (seed 1) "
         "at each point count, on a 2-core machine. Time is wall time; memory is the kernel's peak resident size of the "
         "process (`wait4`'s `ru_maxrss`), not the program's own account. Peers in the same run: PIF (`reconstruct "
         "--no-features`, the thesis's baseline) and Open3D 0.16 screened Poisson at depth 10 (its time includes neither "
         "reading nor the PCA + MST normals, whose time is given apart). Hausdorff and mean distance are in U = 1/200 of "
         "the model's diagonal, by `sharpmesh eval` against the generating mesh.", "",
         "| points | ours: wall s | peak GiB | KiB/point | features s | normals s | Poisson s | meshing s | facets | "
         "Hausdorff U | mean U | valid | PIF wall s | PIF peak GiB | PIF Hausdorff U | Open3D d10 s (+ normals s) | Open3D peak GiB | Open3D Hausdorff U |",
         "|" + "---|" * 18]
for row in rows:
    o = row.get("ours")
    if not o:
        lines.append(f"| {row['points']:,} | failed |" + " |" * 16)
        continue
    g = grouped(o["stages"])
    p, d = row.get("pif"), row.get("open3d")
    lines.append(
        f"| {row['points']:,} | {fmt(o['seconds'])} | {fmt(o['peak_mib'] / 1024, 2)} | {fmt(o['peak_mib'] * 1024 / row['points'], 2)} | "
        f"{fmt(g['features'])} | {fmt(g['normals'])} | {fmt(g['Poisson'])} | {fmt(g['meshing'])} | {o['facets']:,} | "
        f"{fmt(o.get('hausdorff_U'), 2)} | {fmt(o.get('mean_U'), 4)} | {'yes' if o.get('valid') else 'no'} | "
        f"{fmt(p and p['seconds'])} | {fmt(p and p['peak_mib'] / 1024, 2)} | {fmt(p and p.get('hausdorff_U'), 2)} | "
        f"{fmt(d and d['seconds'])} (+ {fmt(d and d.get('normals_seconds'))}) | {fmt(d and d['peak_mib'] / 1024, 2)} | "
        f"{fmt(d and d.get('hausdorff_U'), 2)} |")
measured = [r for r in rows if r.get("ours")]
if len(measured) >= 2:
    import math
    a, b = measured[0], measured[-1]
    exponent = math.log(b["ours"]["seconds"] / a["ours"]["seconds"]) / math.log(b["points"] / a["points"])
    lines += ["", f"Time grows as about n^{exponent:.2f} from {a['points']:,} to {b['points']:,} points; the "
              f"time per point at {b['points']:,} is {b['ours']['seconds'] / b['points'] / (a['ours']['seconds'] / a['points']):.2f} "
              f"times that at {a['points']:,}."]
    pif_rows = [r for r in measured if r.get("pif")]
    if pif_rows:
        lines += ["", "Ours against PIF, wall time ratio: " + ", ".join(
            f"{r['ours']['seconds'] / r['pif']['seconds']:.2f} at {r['points']:,}" for r in pif_rows) + "."]
tiled = [r for r in rows if r.get("tiled") and r.get("ours")]
if tiled:
    lines += ["", "## Tiles against one run", "",
              "`reconstruct --tiles 8` (sharpmesh/tiled.h): the cloud in 8 slabs along its longest axis, normals oriented "
              "once on the whole cloud, each slab meshed with a margin of 6 d' and clipped to its slab, the seams welded; a cut "
              "whose two sides cannot be welded is dropped and its slabs meshed as one. "
              "Valid = closed, manifold, no self-intersecting facet (`sharpmesh eval`).", "",
              "| points | run | wall s | peak GiB | facets | Hausdorff U | mean U | feature recall | valid | boundary edges | cuts welded |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in tiled:
        for label, m in (("one run", r["ours"]), ("8 tiles", r["tiled"])):
            seams = m.get("seams")
            dropped = m.get("dropped_cuts", 0)
            welded = "—" if seams is None else (f"{sum(1 for s in seams if s['stitched'])} of {len(seams) + dropped}"
                                                 + (f" ({dropped} dropped: {m.get('slabs')} slabs meshed)" if dropped else ""))
            lines.append(f"| {r['points']:,} | {label} | {fmt(m['seconds'])} | {fmt(m['peak_mib'] / 1024, 2)} | {m['facets']:,} | "
                         f"{fmt(m.get('hausdorff_U'), 3)} | {fmt(m.get('mean_U'), 4)} | {fmt(m.get('feature_recall'), 3)} | "
                         f"{'yes' if m.get('valid') else 'no'} | {m.get('boundary_edges', '—')} | {welded} |")
if tiles:
    lines += ["", "## Real LiDAR", "",
              "The two AHN3 tiles of Delft in `../shared/data/lidar` (LAZ, read directly), `reconstruct` with defaults. "
              "There is no reference surface to measure against.", "",
              "| tile | wall s | peak GiB | facets |", "|---|---|---|---|"]
    for t in tiles:
        o = t["ours"]
        lines.append(f"| {t['name']} | {fmt(o and o['seconds'])} | {fmt(o and o['peak_mib'] / 1024, 2)} | "
                     f"{'failed' if not o else format(o['facets'], ',')} |")
lines += ["", "![time and memory against points](scale.png)", ""]
open(os.path.join(docs, "scale.md"), "w").write("\n".join(lines))

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
xs = [r["points"] for r in measured]
bottom = [0.0] * len(measured)
for label, _ in stage_groups:
    values = [grouped(r["ours"]["stages"])[label] for r in measured]
    left.bar(range(len(xs)), values, bottom=bottom, label=f"ours: {label}")
    bottom = [b + v for b, v in zip(bottom, values)]
for key, label, marker in (("pif", "PIF", "s--"), ("open3d", "Open3D Poisson d10", "v:")):
    pts = [(i, r[key]["seconds"]) for i, r in enumerate(measured) if r.get(key)]
    if pts:
        left.plot([p[0] for p in pts], [p[1] for p in pts], marker, color="k" if key == "pif" else "grey", label=label)
left.set_xticks(range(len(xs)), [f"{x / 1e6:g}M" for x in xs])
left.set_xlabel("points")
left.set_ylabel("wall time, s")
left.legend(fontsize=8)
right.plot(xs, [r["ours"]["peak_mib"] / 1024 for r in measured], "o-", label="ours")
for key, label, marker in (("pif", "PIF", "s--"), ("open3d", "Open3D Poisson d10", "v:")):
    pts = [(r["points"], r[key]["peak_mib"] / 1024) for r in measured if r.get(key)]
    if pts:
        right.plot([p[0] for p in pts], [p[1] for p in pts], marker, label=label)
right.set_xscale("log")
right.set_yscale("log")
right.set_xlabel("points")
right.set_ylabel("peak resident memory, GiB (kernel)")
right.legend(fontsize=8)
fig.suptitle("fandisk sampled uniformly, 2 cores")
fig.tight_layout()
fig.savefig(os.path.join(docs, "scale.png"), dpi=110)
