#!/usr/bin/env python3
"""Which of several models of the same frames do a COLMAP database's verified pairs support?

Without ground truth, two models that disagree (scripts/compare_models.py) can still be judged by
evidence neither was fitted to: the two-view geometries of another matcher. For every pair the
database verified (at least 30 inlier matches), this prints, per model, the median Sampson
distance in pixels of the pair's inlier matches to the epipolar geometry the model's cameras imply
(its own SIMPLE_RADIAL intrinsics undone first), then over the pairs: the median, the 90th
percentile and the share of pairs over 2 px. Only pairs whose frames every model registers count.

    scripts/pair_support.py DATABASE.db MODEL_DIR [MODEL_DIR ...]

e.g. COLMAP's database from scripts/colmap_baseline.sh against COLMAP's model and comic_sfm's.
"""
import os
import sqlite3
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_models as c  # noqa: E402

def camera(model):
    for l in open(model + '/cameras.txt'):
        if l.startswith('#') or not l.strip(): continue
        v = l.split(); return float(v[4]), float(v[5]), float(v[6]), float(v[7])

def undistort(p, f, cx, cy, k):
    x = (p - [cx, cy]) / f
    u = x.copy()
    for _ in range(10):
        r2 = (u ** 2).sum(1, keepdims=True); u = x / (1 + k * r2)
    return u

if len(sys.argv) < 3:
    print(__doc__.strip().splitlines()[-3].strip(), file=sys.stderr)
    sys.exit(2)
dbpath, models = sys.argv[1], sys.argv[2:]
db = sqlite3.connect(dbpath)
names = dict(db.execute('select image_id,name from images'))
kps = {}
for iid, rows, cols, data in db.execute('select image_id,rows,cols,data from keypoints'):
    kps[iid] = np.frombuffer(data, dtype=np.float32).reshape(rows, cols)[:, :2].astype(float) + 0.0
ms = [(m, c.read_images(m), camera(m)) for m in models]
res = {m: [] for m in models}
for pid, rows, data, cfg in db.execute('select pair_id,rows,data,config from two_view_geometries'):
    if rows < 30 or cfg not in (2, 3, 4, 6): continue
    i2 = pid % 2147483647; i1 = (pid - i2) // 2147483647
    n1, n2 = names[i1], names[i2]
    if not all(n1 in imgs and n2 in imgs for _, imgs, _ in ms): continue
    idx = np.frombuffer(data, dtype=np.uint32).reshape(rows, 2)
    for m, imgs, (f, cx, cy, k) in ms:
        # COLMAP's keypoints put a pixel's centre at +0.5; the models' principal points do not.
        p1 = undistort(kps[i1][idx[:, 0]] - 0.5, f, cx - 0.5, cy - 0.5, k)
        p2 = undistort(kps[i2][idx[:, 1]] - 0.5, f, cx - 0.5, cy - 0.5, k)
        R1, C1 = imgs[n1]; R2, C2 = imgs[n2]
        R = R2 @ R1.T; t = R2 @ (C1 - C2)
        if np.linalg.norm(t) == 0: continue
        t = t / np.linalg.norm(t)
        E = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]]) @ R
        x1 = np.c_[p1, np.ones(len(p1))]; x2 = np.c_[p2, np.ones(len(p2))]
        l2 = x1 @ E.T; l1 = x2 @ E
        r = (x2 * l2).sum(1)
        d = np.abs(r) / np.sqrt(l2[:, 0] ** 2 + l2[:, 1] ** 2 + l1[:, 0] ** 2 + l1[:, 1] ** 2)
        res[m].append(np.median(d) * f)
for m in models:
    a = np.array(res[m])
    print(f'{m}: {len(a)} pairs, median of pair medians {np.median(a):.3f} px, p90 {np.percentile(a, 90):.3f}, pairs over 2 px {np.mean(a > 2) * 100:.1f} %')
