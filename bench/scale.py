"""Runner and report of bench/scale (issue 38). Each command runs as a child
whose peak resident memory is the kernel's (os.wait4's ru_maxrss), so the
figures hold whatever the program says of itself."""
import argparse, json, os, subprocess, sys, time

parser = argparse.ArgumentParser()
parser.add_argument("--build", required=True)
parser.add_argument("--root", required=True)
parser.add_argument("--max", type=int, default=30_000_000)
parser.add_argument("--peers-max", type=int, default=2_000_000)
parser.add_argument("--tiled-min", type=int, default=1_000_000)
parser.add_argument("--no-lidar", action="store_true", help="leave out the real LiDAR tiles")
parser.add_argument("--binary", help="the sharpmesh to measure (default: BUILD's; a copy lets the build go on meanwhile)")
args = parser.parse_args()
binary = args.binary or os.path.join(args.build, "apps/sharpmesh/sharpmesh")
out = os.path.join(args.build, "bench-results/scale")
os.makedirs(out, exist_ok=True)
reference = os.path.join(args.root, ".cache/data/meshes/fandisk.off")
lidar = os.path.join(args.root, "../shared/data/lidar")
sizes = [n for n in (200_000, 1_000_000, 2_000_000, 5_000_000, 10_000_000, 30_000_000) if n <= args.max]


def run(command, log):
    """Wall seconds and peak RSS (MiB) of one child; None when it fails."""
    start = time.monotonic()
    with open(log, "w") as stderr:
        child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=stderr)
        _, status, usage = os.wait4(child.pid, 0)
    seconds = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        print(f"  failed: {' '.join(command)} (see {log})", file=sys.stderr)
        return None
    return {"seconds": seconds, "peak_mib": usage.ru_maxrss / 1024}


def cached(path, make):
    if os.path.exists(path):
        return json.load(open(path))
    result = make()
    if result is not None:
        json.dump(result, open(path, "w"), indent=1)
    return result


def evaluate(mesh, tag):
    report = f"{tag}.eval.json"
    if not os.path.exists(report):
        subprocess.run([binary, "eval", mesh, "--reference", reference, "--json", report, "-q"], check=True)
    e = json.load(open(report))["evaluation"]
    t = e["topology"]
    result = {"facets": e["facets"], "hausdorff_U": e["hausdorff"]["U"], "mean_U": e["mean"]["U"],
              "valid": t["closed"] and t["manifold"] and not t["self_intersecting"], "boundary_edges": t["boundary_edges"]}
    edges = f"{tag}.edges.txt"
    if os.path.exists(edges):
        features = f"{tag}.features.json"
        if not os.path.exists(features):
            subprocess.run([binary, "eval-features", edges, "--reference", reference, "--report", features, "-q"], check=True)
        result["feature_recall"] = json.load(open(features))["evaluation"]["recall"]
    return result


def ours(cloud, tag, extra=()):
    def make():
        measured = run([binary, "reconstruct", cloud, "-o", f"{tag}.ply", "--report", f"{tag}.report.json", "-q", *extra,
                        *([] if "--no-features" in extra else ["--sharp-edges", f"{tag}.edges.txt"])],
                       f"{tag}.log")
        if measured is None:
            return None
        report = json.load(open(f"{tag}.report.json"))
        measured["stages"] = {s["name"]: s["seconds"] for s in report["stages"]}
        measured["stage_peak_mib"] = {s["name"]: s["peak_memory_mib"] for s in report["stages"]}
        measured["facets"] = report["counts"]["facets"]
        return measured
    return cached(f"{tag}.json", make)


def open3d_poisson(oriented, tag):
    script = f"""
import open3d as o3d
pcd = o3d.io.read_point_cloud({oriented!r})
mesh, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=10)
box = pcd.get_axis_aligned_bounding_box()
margin = 0.05 * (box.get_max_bound() - box.get_min_bound()).max()
mesh = mesh.crop(o3d.geometry.AxisAlignedBoundingBox(box.get_min_bound() - margin, box.get_max_bound() + margin))
o3d.io.write_triangle_mesh({tag + '.ply'!r}, mesh)
"""
    return cached(f"{tag}.json", lambda: run(["/usr/bin/python3", "-c", script], f"{tag}.log"))


rows = []
for n in sizes:
    cloud = os.path.join(out, f"fandisk-{n}.ply")
    if not os.path.exists(cloud):
        subprocess.run([binary, "sample", reference, "-n", str(n), "--seed", "1", "-o", cloud, "-q"], check=True)
    print(f"== fandisk {n} points", file=sys.stderr)
    row = {"points": n, "ours": ours(cloud, os.path.join(out, f"fandisk-{n}-ours"))}
    if row["ours"]:
        row["ours"].update(evaluate(os.path.join(out, f"fandisk-{n}-ours.ply"), os.path.join(out, f"fandisk-{n}-ours")))
    if n >= args.tiled_min:
        # The same cloud in 8 slabs (sharpmesh/tiled.h), against the one run.
        tag = os.path.join(out, f"fandisk-{n}-tiled-8")
        row["tiled"] = ours(cloud, tag, ["--tiles", "8"])
        if row["tiled"]:
            row["tiled"].update(evaluate(tag + ".ply", tag))
            tiling = json.load(open(tag + ".report.json"))["tiling"]
            row["tiled"]["seams"] = tiling["seams"]
            row["tiled"]["dropped_cuts"] = tiling.get("merged_seams", 0)
            row["tiled"]["slabs"] = len(tiling["tiles"])
    if n <= args.peers_max:
        tag = os.path.join(out, f"fandisk-{n}-pif")
        row["pif"] = ours(cloud, tag, ["--no-features"])
        if row["pif"]:
            row["pif"].update(evaluate(tag + ".ply", tag))
        oriented = os.path.join(out, f"fandisk-{n}.pca-mst.ply")
        normals = cached(oriented + ".json", lambda: run(
            [binary, "clean", cloud, "-o", oriented, "--normals", "pca", "--normal-k", "18", "--orient", "--orient-k", "18",
             "--no-winding-repair", "-q"], oriented + ".log"))
        tag = os.path.join(out, f"fandisk-{n}-open3d-10")
        row["open3d"] = open3d_poisson(oriented, tag) if normals else None
        if row["open3d"]:
            row["open3d"].update(evaluate(tag + ".ply", tag))
            row["open3d"]["normals_seconds"] = normals["seconds"]
    rows.append(row)

tiles = []
for name in () if args.no_lidar else ("ahn3_cropped_1", "ahn3_cropped_2"):
    path = os.path.join(lidar, name + ".laz")
    if not os.path.exists(path):
        continue
    print(f"== {name}", file=sys.stderr)
    tiles.append({"name": name, "ours": ours(path, os.path.join(out, name + "-ours"))})

json.dump({"fandisk": rows, "lidar": tiles}, open(os.path.join(out, "summary.json"), "w"), indent=1)
subprocess.run(["/usr/bin/python3", os.path.join(args.root, "bench/scale_report.py"), os.path.join(out, "summary.json"),
                os.path.join(args.root, "docs")], check=True)
