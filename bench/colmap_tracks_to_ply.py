#!/usr/bin/env python3
"""Tracks of a COLMAP text model as a PLY with normals for Poisson meshers:
PCA over 20 neighbours, oriented towards the cameras that observed each track.
Usage: colmap_tracks_to_ply.py MODEL_TXT_DIR OUT.ply SUMMARY.json"""
import json, sys
import numpy as np
from scipy.spatial import cKDTree
model, ply, summary = sys.argv[1:4]
def quat_to_r(w, x, y, z):
    return np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)], [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)], [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])
centres = {}
lines = [l for l in open(f"{model}/images.txt") if not l.startswith("#")]
for header in lines[0::2]:
    v = header.split()
    r = quat_to_r(*map(float, v[1:5]))
    centres[int(v[0])] = -r.T @ np.array(list(map(float, v[5:8])))
pts, errs, views, colors = [], [], [], []
for l in open(f"{model}/points3D.txt"):
    if l.startswith("#") or not l.strip(): continue
    v = l.split()
    pts.append(list(map(float, v[1:4]))); colors.append(v[4:7]); errs.append(float(v[7]))
    views.append([int(i) for i in v[8::2]])
pts = np.array(pts)
_, nn = cKDTree(pts).query(pts, k=min(20, len(pts)))
normals = np.zeros_like(pts)
for i, idx in enumerate(nn):
    q = pts[idx] - pts[idx].mean(axis=0)
    n = np.linalg.eigh(q.T @ q)[1][:, 0]
    towards = np.mean([centres[c] for c in views[i]], axis=0) - pts[i]
    normals[i] = n if n @ towards > 0 else -n
with open(ply, "w") as f:
    f.write(f"ply\nformat ascii 1.0\nelement vertex {len(pts)}\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
    for p, n, c in zip(pts, normals, colors):
        f.write(f"{p[0]} {p[1]} {p[2]} {n[0]} {n[1]} {n[2]} {c[0]} {c[1]} {c[2]}\n")
json.dump({"tracks": len(pts), "mean_reprojection_error_px": float(np.mean(errs)),
           "mean_track_length": float(np.mean([len(v) for v in views]))}, open(summary, "w"), indent=2)
