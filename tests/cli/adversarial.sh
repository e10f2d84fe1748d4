#!/usr/bin/env bash
# Adversarial inputs (issue 7): adversarial.sh CASE SHARPMESH_BINARY DATA_DIR
# Each case feeds one hostile input to every command that reads that kind of
# data, and states the outcome expected of each: success with an output that
# reads back, or exit code 1 (the data cannot be used) or 2 (the parameters
# cannot be used) with a one-line message and no output left behind. Never a
# crash, a hang (ctest's timeout) or a temporary file.
source "$(dirname "$0")/setup.sh"

# expect OUTCOME OUTPUT command...: OUTCOME is ok, 1 or 2, as above.
expect() {
  local outcome=$1 output=$2; shift 2
  rm -f "$output"
  "$@" >stdout.txt 2>stderr.txt
  local rc=$?
  ls -a | grep -q '\.tmp\.' && fail "$*: a temporary file was left behind"
  if [[ $outcome == ok ]]; then
    [[ $rc -eq 0 ]] || { cat stderr.txt >&2; fail "$*: exit code $rc, expected success"; }
    if [[ -n "$output" ]]; then
      [[ -e "$output" ]] || fail "$*: exit 0 but no output $output"
      case "$output" in  # point sets and meshes read back; polylines may be empty (no feature found)
        *.ply|*.xyz) $bin info "$output" --no-spacing -q >/dev/null 2>&1 || fail "$*: the output $output does not read back" ;;
      esac
    fi
    echo "  ok     $*"
    return 0
  fi
  [[ $rc -eq $outcome ]] || { cat stderr.txt >&2; fail "$*: exit code $rc, expected $outcome"; }
  [[ $(grep -c '^sharpmesh: ' stderr.txt) -eq 1 ]] || { cat stderr.txt >&2; fail "$*: expected a one-line message"; }
  tail -n 1 stderr.txt | grep -q '^sharpmesh: ' || { cat stderr.txt >&2; fail "$*: the message is not the last line"; }
  [[ -z "$output" || ! -e "$output" ]] || fail "$*: output $output left behind after an error"
  echo "  error  $* -> $(tail -n 1 stderr.txt)"
}

# Every command that reads a point cloud, with the toolbox's options switched
# on: point_commands CLOUD "OUTCOMES" (info, clean, clean, features,
# reconstruct --no-features, reconstruct).
point_commands() {
  local cloud=$1 outcomes
  read -r -a outcomes <<<"$2"
  [[ ${#outcomes[@]} -eq 6 ]] || fail "point_commands needs 6 outcomes"
  expect ${outcomes[0]} "" $bin info "$cloud" -q
  expect ${outcomes[1]} out.ply $bin clean "$cloud" -o out.ply --outliers 5 --outliers-sigma 3 --smooth 24 --normals jet --orient -q
  expect ${outcomes[2]} out.ply $bin clean "$cloud" -o out.ply --grid 2 --random 10 --seed 1 -q
  expect ${outcomes[3]} out.txt $bin features "$cloud" -o out.txt --edge-points e.ply -q
  rm -f e.ply
  expect ${outcomes[4]} out.ply $bin reconstruct "$cloud" -o out.ply --no-features -q
  expect ${outcomes[5]} out.ply $bin reconstruct "$cloud" -o out.ply -q
}

# Every command that reads a mesh: mesh_commands MESH "OUTCOMES" (sample,
# eval of the mesh, eval against it, eval-features against it).
mesh_commands() {
  local mesh=$1 outcomes
  read -r -a outcomes <<<"$2"
  [[ ${#outcomes[@]} -eq 4 ]] || fail "mesh_commands needs 4 outcomes"
  expect ${outcomes[0]} out.ply $bin sample "$mesh" -n 2000 -o out.ply --sharp-edges out.txt -q
  rm -f out.txt
  expect ${outcomes[1]} "" $bin eval "$mesh" --reference "$mesh" --samples 2000 -q
  expect ${outcomes[2]} "" $bin eval "$data/meshes/cube.off" --reference "$mesh" --samples 2000 -q
  printf '2 0 0 0 1 1 1\n' > one.polylines.txt
  expect ${outcomes[3]} "" $bin eval-features one.polylines.txt --reference "$mesh" -q
}

points() {  # points KIND FILE
  python3 - "$1" "$2" <<'PY'
import math, random, sys
kind, path = sys.argv[1], sys.argv[2]
random.seed(1)
def sphere(n, scale=1.0, offset=(0.0, 0.0, 0.0)):
    out = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n; r = math.sqrt(1 - z * z); a = i * 2.399963
        out.append((offset[0] + scale * r * math.cos(a), offset[1] + scale * r * math.sin(a), offset[2] + scale * z))
    return out
rows = {
    "duplicated": lambda: [(0.5, 0.25, 1.0)] * 2000,
    "each-twice": lambda: sphere(1500) + sphere(1500),
    "coplanar": lambda: [(random.random(), random.random(), 0.0) for _ in range(2000)],
    "tilted-plane": lambda: [(x, y, 0.3 * x - 0.7 * y) for x, y in ((random.random(), random.random()) for _ in range(2000))],
    "collinear": lambda: [(t / 1999, 2 * t / 1999, 3 * t / 1999) for t in range(2000)],
    "four-points": lambda: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
    "huge-coordinates": lambda: sphere(2000, 1e30),
    "tiny-coordinates": lambda: sphere(2000, 1e-30),
    "far-from-origin": lambda: sphere(2000, 1.0, (1e12, -1e12, 1e12)),
    "exact-sphere": lambda: sphere(1000),
    "scale-1e-30": lambda: sphere(2000, 1e-30),
    "scale-1e100": lambda: sphere(2000, 1e100),
}[kind]()
with open(path, "w") as f:
    for p in rows: f.write("%r %r %r\n" % p)
PY
}

case "$case_name" in
  duplicated) points $case_name c.xyz; point_commands c.xyz "1 1 1 1 1 1" ;;  # no extent
  each-twice|tilted-plane|huge-coordinates|tiny-coordinates|far-from-origin) points $case_name c.xyz; point_commands c.xyz "ok ok ok ok ok ok" ;;
  coplanar|collinear) points $case_name c.xyz; point_commands c.xyz "ok ok ok ok 1 1" ;;  # no surface encloses a flat cloud
  four-points) points $case_name c.xyz; point_commands c.xyz "ok 2 1 1 1 1" ;;  # k = 5 needs more points; too few to reconstruct
  far-from-origin-accuracy|extreme-scales)  # recentring and rescaling: the sphere comes out as well anywhere and at any size
    check_sphere() {  # check_sphere MESH SCALE OFFSET: every vertex within 5% of the sphere
      python3 - "$@" <<'PY' || fail "the sphere in $1 is distorted"
import struct, sys
path, scale, offset = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
center = (offset, -offset, offset)
data = open(path, "rb").read()
header, body = data.split(b"end_header\n", 1)
n = int([l for l in header.split(b"\n") if l.startswith(b"element vertex")][0].split()[2])
props = [l for l in header.split(b"\n") if l.startswith(b"property") and b"list" not in l]
size = 8 if b"double" in props[0] else 4
fmt = "<" + ("d" if size == 8 else "f") * 3
step = size * len(props)
err = max(abs(sum(((c - o) / scale) ** 2 for c, o in zip(struct.unpack_from(fmt, body, i * step), center)) ** 0.5 - 1) for i in range(n))
assert n > 20 and err < 0.05, (n, err)
PY
    }
    if [[ $case_name == far-from-origin-accuracy ]]; then
      points far-from-origin c.xyz
      $bin reconstruct c.xyz -o m.ply --no-features -q || fail "reconstruct failed far from the origin"
      check_sphere m.ply 1 1e12
    else
      for kind in scale-1e-30 scale-1e100 exact-sphere; do
        points $kind $kind.xyz
        scale=${kind#scale-}; [[ $kind == exact-sphere ]] && scale=1
        $bin reconstruct $kind.xyz -o $kind.ply -q || fail "reconstruct failed on $kind"
        check_sphere $kind.ply "$scale" 0
      done
    fi ;;
  nan-inf-rows)
    points far-from-origin c.xyz
    sed -i '500s/.*/inf 0 0/; 900s/.*/0 -inf nan/' c.xyz
    point_commands c.xyz "1 1 1 1 1 1"
    grep -q "line 500" stderr.txt || fail "the message does not name the first bad line" ;;
  huge-headers)  # headers declaring 10^12 elements on tiny files: refused before any allocation
    printf 'ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n' > a.ply
    printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty double x\nproperty double y\nproperty double z\nelement face 1000000000000\nproperty list uchar int vertex_indices\nend_header\n0123' > b.ply
    printf 'OFF\n1000000000000 1000000000000 0\n0 0 0\n' > c.off
    printf 'solid\n' > d.stl; head -c 80 /dev/zero > e.stl; printf '\xff\xff\xff\x7f' >> e.stl
    printf '1000000000000 0 0 0\n' > f.polylines.txt
    # 4 GB of address space, except under AddressSanitizer (its shadow memory reserves terabytes).
    limit=4000000
    # (no pipe into grep -q: under pipefail an early grep exit kills ldd with SIGPIPE)
    [[ "$(ldd "$bin")" == *libasan* ]] && limit=unlimited
    for f in a.ply b.ply c.off; do ( ulimit -v $limit; point_commands $f "1 1 1 1 1 1" ) || exit 1; done
    for f in b.ply c.off d.stl e.stl; do ( ulimit -v $limit; mesh_commands $f "1 1 1 1" ) || exit 1; done
    ( ulimit -v $limit; expect 1 "" $bin eval-features f.polylines.txt --reference "$data/meshes/cube.off" -q ) || exit 1 ;;
  degenerate-meshes)
    printf 'OFF\n3 1 0\n0 0 0\n1 1 1\n2 2 2\n3 0 1 2\n' > flat.off            # one zero-area facet
    printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' > index.off          # index out of range
    printf 'OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n' > nan.off          # NaN vertex
    printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 0 3\n' > repeated.off  # a facet repeating a vertex
    printf 'v 0 0 0\nv 1 0 0\nf 1 2 3\n' > short.obj
    mesh_commands flat.off "1 1 1 ok"        # nothing to sample or measure; no sharp edge to compare with
    mesh_commands index.off "1 1 1 1"
    mesh_commands nan.off "1 1 1 1"
    mesh_commands repeated.off "ok ok ok ok"  # the degenerate facet is dropped, the other one is used
    mesh_commands short.obj "1 1 1 1" ;;
  absurd-parameters)  # k >= n, zero and negative radii and sizes: usage errors, except sizes that merely give a coarse result
    points each-twice c.xyz
    expect 2 out.ply $bin clean c.xyz -o out.ply --smooth 5000
    expect 2 out.ply $bin clean c.xyz -o out.ply --outliers-sigma 3 --sigma-k 100000
    expect 2 out.ply $bin clean c.xyz -o out.ply --normals pca --normal-k 0
    expect 2 out.ply $bin clean c.xyz -o out.ply --grid 0
    expect 2 out.ply $bin clean c.xyz -o out.ply --grid -1
    expect 2 out.ply $bin clean c.xyz -o out.ply --grid 1e-300
    for option in "--offset-radius 0" "--offset-radius -1" "--convolution-radius -0.5" "--t1 0" "--t2 -1" "--cluster-k 0" "--cluster-angle -5" \
                  "--successor-k 0" "--junction-factor -1" "--denoise-k 100000"; do
      expect 2 out.txt $bin features c.xyz -o out.txt $option
    done
    expect ok out.txt $bin features c.xyz -o out.txt --cluster-k 100000  # a cluster may hold every point
    for option in "--delta 0" "--delta -1" "--delta 1e-9" "--ball-radius 0" "--ball-radius -1" "--max-facets 10" \
                  "--poisson-spacing -1" "--poisson-spacing 5" "--poisson-spacing nan" "--poisson-screening -1" "--poisson-screening nan" "--poisson-screening-noisy -1"; do
      expect 2 out.ply $bin reconstruct c.xyz -o out.ply --no-features $option
    done
    expect ok out.ply $bin reconstruct c.xyz -o out.ply --no-features --delta 1e300  # facets as large as the object allows
    for option in "--classes 2" "--classes 300" "--classes -1" "--classes x"; do  # classes only exist in LAS/LAZ, 0-255
      expect 2 out.ply $bin reconstruct c.xyz -o out.ply --no-features $option
      expect 2 out.ply $bin clean c.xyz -o out.ply $option
    done
    expect 2 out.ply $bin sample "$data/meshes/cube.off" -o out.ply -n 0
    expect 2 "" $bin eval "$data/meshes/cube.off" --reference "$data/meshes/cube.off" --sharp-angle -5
    expect 2 "" $bin eval-features /dev/null --reference "$data/meshes/cube.off" --tolerance -1 ;;
  interrupt)  # Ctrl-C during a long run: exit 130, nothing written
    $bin sample "$data/meshes/fandisk.off" -n 100000 --seed 1 -o s.ply -q || fail "sample failed"
    # SIGINT as soon as the first progress line arrives: mid-run, whatever the machine's speed.
    mkfifo progress
    $bin reconstruct s.ply -o m.ply --delta 2 >/dev/null 2>progress &
    pid=$!
    exec 3<progress
    IFS= read -r -u 3 first || fail "no progress line before the end"
    kill -INT $pid
    cat <&3 >stderr.txt  # until the program exits and closes its end
    exec 3<&-
    wait $pid
    rc=$?
    [[ $rc -eq 130 ]] || fail "exit code $rc after SIGINT, expected 130"
    [[ ! -e m.ply ]] || fail "output written despite the interruption"
    ls -a | grep -q '\.tmp\.' && fail "a temporary file was left behind"
    tail -n 1 stderr.txt | grep -q "interrupted" || fail "no message after SIGINT" ;;
  deterministic)  # same input, parameters and seed: byte-identical outputs, 1 thread or all
    $bin sample "$data/meshes/fandisk.off" -n 20000 --seed 4 -o s.ply -q || fail "sample failed"
    for threads in 1 0; do
      $bin clean s.ply -o c$threads.ply --outliers-sigma 3 --smooth 18 --normals jet --orient --threads $threads -q || fail "clean failed"
      $bin features s.ply -o f$threads.txt --edge-points e$threads.ply --threads $threads -q || fail "features failed"
      $bin reconstruct s.ply -o m$threads.ply --threads $threads -q || fail "reconstruct failed"
      $bin sample m$threads.ply -n 5000 --seed 2 -o r$threads.ply --threads $threads -q || fail "sample failed"
    done
    for f in c f e m r; do
      ext=$([[ $f == f ]] && echo txt || echo ply)
      cmp -s ${f}1.$ext ${f}0.$ext || fail "${f}1.$ext and ${f}0.$ext differ: not deterministic across thread counts"
    done ;;
  deterministic-stereo)  # tracks, soup and mesh byte-identical across runs and thread counts
    $bin make-scene sc --views 4 --width 200 --height 150 --samples 4000 --seed 5 -q || fail "make-scene failed"
    for run in 1 0 0b; do
      $bin stereo sc -o m$run.ply --soup s$run.ply --tracks-out t$run.ply --threads ${run%b} -q || fail "stereo failed"
    done
    for f in t s m; do
      cmp -s ${f}1.ply ${f}0.ply || fail "${f}1.ply and ${f}0.ply differ: not deterministic across thread counts"
      cmp -s ${f}0.ply ${f}0b.ply || fail "${f}0.ply and ${f}0b.ply differ: not deterministic across runs"
    done ;;
  stereo-inputs)  # broken camera models and tracks in every stereo reader
    $bin make-scene sc --views 3 --width 64 --height 48 --samples 500 -q || fail "make-scene failed"
    cp -r sc/sparse sparse-ok
    head -c 300 sparse-ok/images.txt > sc/sparse/images.txt
    expect 1 m.ply $bin stereo sc -o m.ply
    expect 1 "" $bin eval-stereo sc/ground_truth.ply --reference sc/ground_truth.ply --cameras sc/sparse
    cp sparse-ok/images.txt sc/sparse/images.txt
    sed -i 's/^\([0-9]* [-0-9.e]* [-0-9.e]*\) [-0-9.e]*/\1 nan/' sc/sparse/points3D.txt
    expect 1 m.ply $bin stereo sc -o m.ply
    cp sparse-ok/points3D.txt sc/sparse/points3D.txt
    printf 'NVM_V3\n\n1000000000000\n' > big.nvm
    expect 1 m.ply $bin stereo big.nvm -o m.ply
    printf '# Bundle file v0.3\n1000000000 1000000000\n' > bundle.out; printf 'a.png\n' > list.txt
    expect 1 m.ply $bin stereo bundle.out -o m.ply
    printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty double x\nproperty double y\nproperty double z\nproperty list uchar uint views\nend_header\n' > t.ply
    expect 1 m.ply $bin stereo sc -o m.ply --tracks t.ply ;;
  *) fail "unknown case" ;;
esac
echo "PASS [$case_name]"
