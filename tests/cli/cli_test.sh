#!/usr/bin/env bash
# Command-line tests: cli_test.sh CASE SHARPMESH_BINARY DATA_DIR
# Failure cases check: exit code 1 or 2, a one-line message naming the
# problem, and no output file left behind (not even a temporary).
source "$(dirname "$0")/setup.sh"

# expect_error CODE PATTERN OUTPUT -- command...
expect_error() {
  local code=$1 pattern=$2 output=$3; shift 3
  "$@" >stdout.txt 2>stderr.txt
  local rc=$?
  [[ $rc -eq $code ]] || { cat stderr.txt >&2; fail "exit code $rc, expected $code"; }
  # Progress lines may come first; the error is one line, the last one.
  [[ $(grep -c '^sharpmesh: ' stderr.txt) -eq 1 ]] || { cat stderr.txt >&2; fail "expected a one-line message"; }
  tail -n 1 stderr.txt | grep -q '^sharpmesh: ' || { cat stderr.txt >&2; fail "the message is not the last line"; }
  tail -n 1 stderr.txt | grep -q -- "$pattern" || { cat stderr.txt >&2; fail "message does not mention '$pattern'"; }
  [[ -z "$output" || ! -e "$output" ]] || fail "output $output was left behind"
  ls -a | grep -q '\.tmp\.' && fail "a temporary file was left behind"
  return 0
}

cloud() {  # cloud N FILE: N points on a small sphere-like spiral (no two equal)
  python3 - "$1" "$2" <<'PY'
import math, sys
n, path = int(sys.argv[1]), sys.argv[2]
with open(path, "w") as f:
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n; r = math.sqrt(1 - z * z); a = i * 2.399963
        f.write(f"{r*math.cos(a)} {r*math.sin(a)} {z}\n")
PY
}

case "$case_name" in
  help)
    for cmd in "" info clean sample eval reconstruct features eval-features make-scene eval-stereo decimate; do
      $bin $cmd --help >out.txt || fail "--help of '$cmd' failed"
      grep -q "Usage" out.txt || fail "--help of '$cmd' shows no usage"
    done ;;
  version) $bin --version | grep -c "sharpmesh" >/dev/null || fail "no version" ;;
  info)
    cloud 500 c.xyz
    $bin info c.xyz --report r.json >out.txt || fail "info failed"
    grep -q "points: *500" out.txt || fail "wrong count"
    python3 -c "import json; r=json.load(open('r.json')); assert r['counts']['points']==500 and r['average_spacing']['value']>0" || fail "bad report" ;;
  clean)
    cloud 2000 c.xyz
    echo "50 50 50" >> c.xyz
    $bin clean c.xyz -o out.ply --outliers-sigma 3 --sigma-k 24 --smooth 24 --normals jet --orient --report r.json -q || fail "clean failed"
    python3 -c "import json; r=json.load(open('r.json')); c=r['counts']; assert c['removed_outliers_sigma']>=1 and c['output']>=1990, c" || fail "bad counts"
    $bin info out.ply | grep -c "normals: *yes" >/dev/null || fail "no normals written" ;;
  sample-eval)
    $bin sample "$data/meshes/cube.off" -n 5000 --seed 3 -o s.ply --sharp-edges e.txt -q || fail "sample failed"
    [[ $(wc -l < e.txt) -eq 12 ]] || fail "cube should have 12 sharp polylines, got $(wc -l < e.txt)"
    $bin eval "$data/meshes/cube.off" --reference "$data/meshes/cube.off" --json e.json >out.txt || fail "eval failed"
    python3 -c "import json; e=json.load(open('e.json'))['evaluation']; assert e['hausdorff']['value']<1e-9 and e['topology']['closed']" || fail "bad eval" ;;
  reconstruct-small)
    $bin sample "$data/meshes/fandisk.off" -n 20000 --seed 1 -o s.ply -q || fail "sample failed"
    python3 - "$bin" <<'PY' || fail "reconstruct failed, or its peak memory disagrees with the kernel's"
import json, resource, subprocess, sys
subprocess.run([sys.argv[1], "reconstruct", "s.ply", "-o", "m.off", "--no-features", "--report", "r.json", "-q"], check=True)
kernel_peak_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # of the largest child: reconstruct
r = json.load(open("r.json"))
stage_peak = max(s["peak_memory_mib"] for s in r["stages"])
# No stage above the process's own peak, and the report's peak is the kernel's (up to the pages the report's writing touches).
assert stage_peak <= r["peak_memory_mib"] + 1e-9 and abs(r["peak_memory_mib"] - kernel_peak_mib) <= 0.05 * kernel_peak_mib + 4, (stage_peak, r["peak_memory_mib"], kernel_peak_mib)
PY
    $bin eval m.off --reference "$data/meshes/fandisk.off" --json e.json -q || fail "eval failed"
    python3 - <<'PY' || fail "reconstruction out of bounds"
import json
e = json.load(open("e.json"))["evaluation"]
assert e["topology"]["closed"] and e["topology"]["manifold"] and not e["topology"]["self_intersecting"], e["topology"]
assert e["hausdorff"]["fraction_of_diagonal"] < 0.025, e["hausdorff"]
r = json.load(open("r.json"))
names = [s["name"] for s in r["stages"]]
# The steps of 7.3 in their order, between reading and writing; repairs may add stages between them.
steps = ["spacing", "normals", "poisson", "refinement", "trim", "write"]
it = iter(names)
assert names[0] == "read" and names[-1] == "write" and all(n in it for n in steps), names
assert not {"detection", "clustering", "polylines", "snapping"} & set(names), names  # --no-features
PY
    ;;
  reconstruct-features)  # Chapter 7 end to end: the cube's 12 edges come out as mesh edges
    $bin sample "$data/meshes/cube.off" -n 20000 --seed 2 -o s.ply -q || fail "sample failed"
    $bin reconstruct s.ply -o m.off --delta 5 --sharp-edges e.txt --report r.json -q || fail "reconstruct failed"
    # Known miss (see README): on this sample one edge is traced only over two
    # thirds of its length, so the bound is recall > 0.95, not 1.
    $bin eval-features e.txt --reference "$data/meshes/cube.off" --json f.json -q || fail "eval-features failed"
    $bin eval m.off --reference "$data/meshes/cube.off" --json e.json -q || fail "eval failed"
    $bin reconstruct s.ply -o pif.off --delta 5 --no-features -q || fail "PIF reconstruct failed"
    $bin eval pif.off --reference "$data/meshes/cube.off" --json pif.json -q || fail "PIF eval failed"
    python3 - <<'PY' || fail "feature-preserving reconstruction out of bounds"
import json
f = json.load(open("f.json"))
f = f.get("evaluation", f)
assert f["recall"] > 0.95 and f["precision"] > 0.99, f
e = json.load(open("e.json"))["evaluation"]
assert e["topology"]["closed"] and e["topology"]["manifold"] and not e["topology"]["self_intersecting"], e["topology"]
# The missed stretch is rounded as in PIF: 1.8-2.6% of the diagonal over
# refinement seeds 0-2, against 4.1% for PIF on the same cloud.
pif = json.load(open("pif.json"))["evaluation"]
assert e["hausdorff"]["fraction_of_diagonal"] < 0.03, e["hausdorff"]
assert e["hausdorff"]["value"] < 0.75 * pif["hausdorff"]["value"], (e["hausdorff"], pif["hausdorff"])
r = json.load(open("r.json"))
p = r["protection"]
assert p["represented_fraction"] == 1.0 and p["uncovered_gaps"] == 0, p
names = [s["name"] for s in r["stages"]]
# Features (7.2) come before the normals and the implicit (7.3); snapping after the trim.
steps = ["spacing", "detection", "clustering", "polylines", "normals", "poisson", "refinement", "trim", "snapping", "write"]
it = iter(names)
assert names[0] == "read" and names[-1] == "write" and all(n in it for n in steps), names
assert r["counts"]["unsnapped_vertices"] <= r["counts"]["snapped_corners"] + r["counts"]["snapped_to_data"], r["counts"]
assert r["parameters"]["snapping"] is True, r["parameters"]
assert r["data_fit"]["points_off_first_mesh"] == 0 and r["data_fit"]["retries"] == 0, r["data_fit"]
assert r["counts"]["normal_source"] == "cvcm", r["counts"]
assert r["counts"]["flattened_vertices"] > 0, r["counts"]
PY
    ;;
  decimate)  # issue 37: a budget reached with the sharp edges kept, closed and valid, and the same from reconstruct
    $bin sample "$data/meshes/fandisk.off" -n 30000 --seed 1 -o s.ply -q || fail "sample failed"
    $bin reconstruct s.ply -o fine.ply --sharp-edges e.txt --report fine.json -q || fail "reconstruct failed"
    $bin decimate fine.ply -o light.ply --feature-curves e.txt --facets 1500 --report d.json -q || fail "decimate failed"
    $bin reconstruct s.ply -o direct.ply --facets 1500 --report r.json -q || fail "reconstruct --facets failed"
    for m in fine light direct; do $bin eval $m.ply --reference "$data/meshes/fandisk.off" --json $m.eval.json -q || fail "eval $m failed"; done
    python3 - <<'PY' || fail "decimation out of bounds"
import json
d = json.load(open("d.json"))
assert d["counts"]["output_facets"] == 1500 and not d["counts"]["budget_missed"], d["counts"]
assert d["counts"]["sharp_edges"] > 0 and d["self_intersections"]["remaining_pairs"] == 0, d
r = json.load(open("r.json"))
assert r["decimation"]["output_facets"] <= 1500 and r["counts"]["facets"] <= 1500, r["decimation"]
fine, light, direct = (json.load(open(f"{m}.eval.json"))["evaluation"] for m in ("fine", "light", "direct"))
for e in (light, direct):
    t = e["topology"]
    assert t["closed"] and t["manifold"] and not t["self_intersecting"] and t["components"] == 1, t
    # A tenth of the facets: the sharp edges stay about where they were, the
    # surface within a few of the fine mesh's errors.
    assert e["sharp_edges"]["mean"]["value"] < 2.5 * fine["sharp_edges"]["mean"]["value"], (e["sharp_edges"], fine["sharp_edges"])
    assert e["hausdorff"]["value"] < 2 * fine["hausdorff"]["value"], (e["hausdorff"], fine["hausdorff"])
PY
    ;;
  decimate-bad)
    printf 'OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 1 2\n' > nm.off
    expect_error 1 "nm.off: decimation needs an oriented, edge- and vertex-manifold mesh" "out.ply" $bin decimate nm.off -o out.ply --facets 2
    expect_error 2 "needs --facets or --tolerance" "out.ply" $bin decimate nm.off -o out.ply
    expect_error 2 "tolerance" "out.ply" $bin decimate nm.off -o out.ply --tolerance 3
    expect_error 1 "nope.off" "out.ply" $bin decimate nope.off -o out.ply --facets 10 ;;
  reconstruct-tiles)  # slabs welded into one mesh, as valid as one run's, each seam reported
    $bin sample "$data/meshes/fandisk.off" -n 30000 --seed 4 -o s.ply -q || fail "sample failed"
    $bin reconstruct s.ply -o m.ply --tiles 3 --sharp-edges e.txt --report r.json -q || fail "tiled reconstruct failed"
    $bin eval m.ply --reference "$data/meshes/fandisk.off" --json e.json -q || fail "eval failed"
    python3 - <<'PY' || fail "tiled reconstruction out of bounds"
import json
e = json.load(open("e.json"))["evaluation"]
assert e["topology"]["closed"] and e["topology"]["manifold"] and not e["topology"]["self_intersecting"], e["topology"]
assert e["topology"]["components"] == 1 and e["hausdorff"]["fraction_of_diagonal"] < 0.02, e
t = json.load(open("r.json"))["tiling"]
assert len(t["tiles"]) == 3 and len(t["seams"]) == 2 and all(s["stitched"] for s in t["seams"]), t
assert sum(tile["points"] for tile in t["tiles"]) > 30000, t  # the margins overlap
PY
    [[ -s e.txt ]] || fail "no sharp edges written"
    expect_error 2 "tiles" "out.ply" $bin reconstruct s.ply -o out.ply --tiles 0
    expect_error 2 "facet budget" "out.ply" $bin reconstruct s.ply -o out.ply --tiles 2 --facets 1000 ;;
  features-given)
    $bin sample "$data/meshes/cube.off" -n 5000 --seed 2 -o s.ply -q || fail "sample failed"
    printf '2 -1 -1 -1 1 -1 -1\n' > one.txt
    $bin reconstruct s.ply -o m.off --features one.txt --sharp-edges e.txt -q || fail "reconstruct with given features failed"
    [[ $(wc -l < e.txt) -eq 1 ]] || fail "one given polyline should give one feature polyline"
    printf '2 0 0 nan 1 1 1\n' > bad.txt
    expect_error 1 "bad.txt" "out.off" $bin reconstruct s.ply -o out.off --features bad.txt
    expect_error 2 "excludes" "out.off" $bin reconstruct s.ply -o out.off --features one.txt --no-features ;;
  fandisk-200k)  # acceptance claim: the Chapter 7 pipeline on fandisk at 200k points
    $bin sample "$data/meshes/fandisk.off" -n 200000 --seed 1 -o s.ply -q || fail "sample failed"
    $bin reconstruct s.ply -o m.ply -q || fail "reconstruct failed"
    $bin eval m.ply --reference "$data/meshes/fandisk.off" --json e.json -q || fail "eval failed"
    python3 - <<'PY' || fail "fandisk 200k out of bounds"
import json
e = json.load(open("e.json"))["evaluation"]
t = e["topology"]
assert t["closed"] and t["manifold"] and not t["self_intersecting"], t
assert e["hausdorff"]["fraction_of_diagonal"] < 0.006, e["hausdorff"]
assert e["sharp_edges"]["mean"]["U"] < 0.2, e["sharp_edges"]
PY
    ;;
  report-json)
    cloud 300 c.xyz
    expect_error 2 "missing" "" $bin info c.xyz --report missing/r.json ;;
  missing-file) expect_error 1 "nope.ply" "out.ply" $bin clean nope.ply -o out.ply ;;
  unknown-extension) echo "0 0 0" > c.abc; expect_error 1 "unknown point-set format" "out.ply" $bin clean c.abc -o out.ply ;;
  truncated-ply)
    cloud 200 c.xyz; $bin clean c.xyz -o full.ply -q || fail "setup"
    head -c 2000 full.ply > cut.ply
    expect_error 1 "cut.ply.*truncated" "out.ply" $bin clean cut.ply -o out.ply ;;
  huge-header)
    printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0123' > h.ply
    expect_error 1 "h.ply" "out.ply" $bin reconstruct h.ply -o out.ply --no-features ;;
  nan-coordinate)
    cloud 100 c.xyz; echo "nan 0 0" >> c.xyz
    expect_error 1 "c.xyz: line 101" "out.ply" $bin reconstruct c.xyz -o out.ply --no-features ;;
  empty-cloud) : > e.xyz; expect_error 1 "at least" "out.ply" $bin reconstruct e.xyz -o out.ply --no-features ;;
  three-points) printf '0 0 0\n1 0 0\n0 1 0\n' > t.xyz; expect_error 1 "at least" "out.ply" $bin reconstruct t.xyz -o out.ply --no-features ;;
  k-too-large) cloud 50 c.xyz; expect_error 2 "k = 100" "out.ply" $bin clean c.xyz -o out.ply --smooth 100 ;;
  zero-delta) cloud 500 c.xyz; expect_error 2 "delta must be positive" "out.ply" $bin reconstruct c.xyz -o out.ply --no-features --delta 0 ;;
  negative-delta) cloud 500 c.xyz; expect_error 2 "delta must be positive" "out.ply" $bin reconstruct c.xyz -o out.ply --no-features --delta -2 ;;
  delta-too-small) cloud 500 c.xyz; expect_error 2 "max-facets" "out.ply" $bin reconstruct c.xyz -o out.ply --no-features --delta 0.0001 ;;
  delta-too-small-features) cloud 500 c.xyz; expect_error 2 "max-facets" "out.ply" $bin reconstruct c.xyz -o out.ply --delta 0.0001 ;;
  missing-output-folder) cloud 100 c.xyz; expect_error 2 "does not exist" "" $bin clean c.xyz -o no/such/dir/out.ply ;;
  readonly-output-folder)  # a folder the user may not write to, and a file where a folder is expected
    cloud 100 c.xyz; mkdir ro; chmod a-w ro
    runner=()
    if [[ $(id -u) -eq 0 ]]; then
      # Root writes anywhere: the command runs as the unprivileged user nobody,
      # from a copy of the binary it can reach whatever the checkout's folders allow.
      command -v setpriv >/dev/null || { echo "SKIP: running as root and setpriv (util-linux) is missing"; exit 77; }
      cp "$bin" ./sharpmesh; chmod 755 . ./sharpmesh; bin=$PWD/sharpmesh
      runner=(setpriv --reuid=65534 --regid=65534 --clear-groups)
    fi
    expect_error 2 "not writable" "ro/out.ply" "${runner[@]}" $bin clean c.xyz -o ro/out.ply
    expect_error 2 "not a folder" "" $bin clean c.xyz -o c.xyz/out.ply ;;
  bad-option) expect_error 2 "banana" "" $bin reconstruct --delta banana ;;
  time-limit)  # the user's clock: past it, exit 1 and nothing written (reading 20k points alone takes longer than 1 ms)
    cloud 20000 c.xyz; expect_error 1 "time-limit" "out.ply" $bin reconstruct c.xyz -o out.ply --time-limit 0.001 ;;
  make-scene-eval)  # issue 5: a small scene, and eval-stereo of its own ground truth is 100% everywhere
    $bin make-scene sc --views 6 --width 160 --height 120 --samples 3000 --seed 2 -q --report r.json || fail "make-scene failed"
    python3 -c "import json; r=json.load(open('r.json')); assert r['counts']['tracks']>500 and r['reprojection_pixels']['rms']<0.75, r" || fail "bad scene report"
    [[ -f sc/images/view_005.png && -f sc/sparse/points3D.txt && -f sc/dense/fused.ply.vis ]] || fail "scene layout incomplete"
    $bin eval-stereo sc/ground_truth.ply --scene sc --samples 20000 --json e.json --plot e.png -q || fail "eval-stereo failed"
    python3 -c "import json; r=json.load(open('e.json'))['results'][0]; assert r['accuracy'][0]==1 and r['completeness'][0]==1, r" || fail "ground truth is not 100%"
    [[ $(head -c 4 e.png | tail -c 3) == PNG ]] || fail "no PNG plot"
    $bin eval-stereo sc/ground_truth.ply --reference sc/ground_truth.ply --cameras sc/sparse -q --json f.json || fail "--reference/--cameras failed" ;;
  make-scene-bad)
    expect_error 2 "views" "sc" $bin make-scene sc --views 1
    expect_error 2 "does not exist" "" $bin make-scene no/such/sc
    mkdir mine; echo keep > mine/notes.txt
    expect_error 2 "not a sharpmesh scene" "" $bin make-scene mine
    [[ -f mine/notes.txt ]] || fail "a foreign folder was touched" ;;
  eval-stereo-bad)
    $bin sample "$data/meshes/cube.off" -n 100 -o c.ply -q
    expect_error 1 "no/scene" "e.json" $bin eval-stereo "$data/meshes/cube.off" --scene no/scene --json e.json
    expect_error 2 "reference" "" $bin eval-stereo "$data/meshes/cube.off"
    expect_error 2 "exactly one MESH" "miss.ply" $bin eval-stereo "$data/meshes/cube.off" c.ply --scene no/scene --missing miss.ply
    expect_error 2 "use .ply or .xyz" "miss.txt" $bin eval-stereo "$data/meshes/cube.off" --scene no/scene --missing miss.txt
    expect_error 2 "requires --missing" "" $bin eval-stereo "$data/meshes/cube.off" --scene no/scene --missing-threshold 0.01 ;;
  stereo)  # issue 6: a generated scene end to end, with its intermediate outputs and report
    $bin make-scene sc --views 6 --width 320 --height 240 --samples 12000 --seed 3 -q || fail "make-scene failed"
    $bin stereo sc -o m.ply --soup soup.ply --tracks-out t.ply --report r.json -q || fail "stereo failed"
    [[ -s m.ply && -s soup.ply && -s t.ply ]] || fail "outputs missing"
    python3 - <<'PY' || fail "bad stereo report"
import json
r = json.load(open("r.json"))
c = r["counts"]
assert c["tracks"]["input"] > c["tracks"]["kept"] > 1000, c["tracks"]
assert c["soup"]["unique"] > c["soup"]["kept"] > 1000, c["soup"]
assert c["mesh"]["facets"] > 1000, c["mesh"]
names = [s["name"] for s in r["stages"]]
steps = ["tracks", "depth maps", "soup filters", "meshing", "write"]  # 6.3 to 6.5 in their order
it = iter(names)
assert names[0] == "read" and names[-1] == "write" and all(n in it for n in steps), names
f = c["fill"]
assert f["skipped"] == "" and f["surface_facets"] > 0 and 0 < f["added"] <= f["surface_facets"] - f["removed_visibility"], f
assert r["parameters"]["merge_distance"] > 0 and r["parameters"]["max_crossings"] > 0, r["parameters"]
PY
    $bin eval-stereo m.ply --scene sc --samples 20000 --json e.json -q || fail "eval-stereo failed"
    python3 -c "import json; r=json.load(open('e.json'))['results'][0]; assert r['accuracy'][4] > 0.95 and r['completeness'][5] > 0.8, r" \
      || fail "inaccurate or incomplete stereo mesh"
    # --missing: the visible reference samples farther than 0.5% (the 4th threshold) from the mesh.
    $bin eval-stereo m.ply --scene sc --samples 20000 --missing miss.ply -q || fail "eval-stereo --missing failed"
    python3 -c "
import json
e = json.load(open('e.json')); n = e['visible_reference_samples']; c = e['results'][0]['completeness'][3]
count = int([l for l in open('miss.ply', 'rb').read(400).decode('latin-1').split('\\n') if l.startswith('element vertex')][0].split()[2])
assert abs(count - round(n * (1 - c))) <= 1 and count > 0, (count, n, c)" || fail "--missing does not hold the samples completeness misses"
    # --no-fill: the thesis's soup alone, no fill stage, no more complete.
    $bin stereo sc -o nofill.ply --no-fill --report rn.json -q || fail "stereo --no-fill failed"
    $bin eval-stereo nofill.ply --scene sc --samples 20000 --json en.json -q || fail "eval-stereo failed"
    python3 -c "import json; a=json.load(open('e.json'))['results'][0]; b=json.load(open('en.json'))['results'][0]; r=json.load(open('rn.json')); assert r['counts']['fill']['skipped'] == 'disabled' and b['completeness'][4] <= a['completeness'][4] + 0.005, (a['completeness'], b['completeness'])" \
      || fail "--no-fill is not the soup alone"
    # A coarser mesh from the same soup: fewer facets.
    $bin stereo sc -o coarse.ply --size 0.035 --distance 0.01 --report rc.json -q || fail "coarse stereo failed"
    python3 -c "import json; a=json.load(open('r.json')); b=json.load(open('rc.json')); assert b['counts']['mesh']['facets'] < a['counts']['mesh']['facets'] / 3, (a['counts']['mesh'], b['counts']['mesh'])" \
      || fail "--size/--distance do not coarsen"
    # Hole filling: fewer border edges, a report of what was filled.
    $bin stereo sc -o filled.ply --max-hole 0.2 --report rh.json -q || fail "stereo --max-hole failed"
    python3 - <<'PY' || fail "hole filling did not fill"
import json
r = json.load(open("rh.json"))
h = r["counts"]["holes"]
assert h["boundary_cycles"] > 0 and 0 < h["filled"] <= h["boundary_cycles"] and h["added_facets"] > 0, h
assert r["counts"]["mesh"]["facets"] > json.load(open("r.json"))["counts"]["mesh"]["facets"], r["counts"]["mesh"]
assert "hole filling" in [s["name"] for s in r["stages"]] and r["parameters"]["max_hole"] == 0.2, r["stages"]
PY
    $bin eval m.ply --reference m.ply --samples 2000 --report em.json -q || fail "eval failed"
    $bin eval filled.ply --reference m.ply --samples 2000 --report eh.json -q || fail "eval failed"
    python3 -c "import json; a=json.load(open('em.json'))['evaluation']['topology']; b=json.load(open('eh.json'))['evaluation']['topology']; assert b['boundary_edges'] < a['boundary_edges'], (a, b)" \
      || fail "the filled mesh has as many border edges" ;;
  stereo-bad)
    $bin make-scene sc --views 3 --width 64 --height 48 --samples 500 -q || fail "make-scene failed"
    expect_error 1 "no/such" "m.ply" $bin stereo no/such -o m.ply
    expect_error 2 "size bound" "m.ply" $bin stereo sc -o m.ply --size 0
    expect_error 2 "cone angle" "m.ply" $bin stereo sc -o m.ply --min-cone-angle -1
    expect_error 2 "largest hole" "m.ply" $bin stereo sc -o m.ply --max-hole -1
    cp sc/images/view_000.png keep.png
    cp sc/images/view_001.png sc/images/view_000.png
    printf 'not an image' > sc/images/view_001.png
    expect_error 1 "view_001.png" "m.ply" $bin stereo sc -o m.ply
    rm sc/images/view_002.png
    cp keep.png sc/images/view_001.png
    expect_error 1 "view_002.png" "m.ply" $bin stereo sc -o m.ply
    expect_error 1 "view_002.png" "m.ply" $bin stereo sc -o m.ply --images sc/images ;;
  laz-broken) printf 'LASF' > c.laz; expect_error 1 "c.laz: not a LAS file" "out.ply" $bin clean c.laz -o out.ply ;;
  features)
    $bin sample "$data/meshes/cube.off" -n 20000 --seed 3 -o s.ply -q || fail "sample failed"
    $bin features s.ply -o p.polylines.txt --edge-points e.ply --report r.json -q || fail "features failed"
    [[ -s p.polylines.txt ]] || fail "no polyline written"
    head -c 300 e.ply | grep -q "property uchar class" || fail "edge points lack their class"
    python3 - <<'PY' || fail "bad features report"
import json
r = json.load(open("r.json"))
assert [s["name"] for s in r["stages"]] == ["detection", "clustering", "polylines"], r["stages"]  # the three steps of 7.2, nothing else
assert r["counts"]["edge_points"] > 0 and r["counts"]["points"] == 20000, r["counts"]
PY
    $bin eval-features p.polylines.txt --reference "$data/meshes/cube.off" --json f.json -q || fail "eval-features failed"
    python3 -c "import json; e=json.load(open('f.json'))['evaluation']; assert e['recall'] > 0.95 and e['precision'] > 0.95 and e['recalled_corners'] == e['truth_corners'] == 8, e" || fail "the cube's 12 edges and 8 corners are not found"
    # Quiet means quiet, on a model in millimetres too (polylines 160 long).
    $bin sample "$data/meshes/oblong.off" -n 20000 --seed 1 -o o.ply -q || fail "sample failed"
    $bin features o.ply -o o.txt -q 2> err.txt || fail "features on oblong failed"
    [[ ! -s err.txt ]] || fail "features -q wrote to stderr: $(head -c 300 err.txt)" ;;
  features-bad-input)
    printf '0 0 0\n1 0 0\n0 1 0\n' > t.xyz
    expect_error 1 "at least" "p.txt" $bin features t.xyz -o p.txt
    cloud 500 c.xyz
    expect_error 2 "offset radius" "p.txt" $bin features c.xyz -o p.txt --offset-radius -1 ;;
  *) fail "unknown case" ;;
esac
echo "PASS [$case_name]"
