#!/usr/bin/env python3
"""Compares two depth images pixel by pixel: coverage (depth < 1) and depth values.

Both are NumPy .npy files of window depth (f32, row 0 at the bottom, cleared to 1), as written by
`shadowlab render-mesh --npy` and by the peer harness's `gl_depth_bench.py --dump`.

    python3 benches/compare_depth.py ours.npy theirs.npy
"""
import sys

import numpy as np

ours, theirs = (np.load(p).astype(np.float64) for p in sys.argv[1:3])
if ours.shape != theirs.shape:
    sys.exit(f"sizes differ: {ours.shape} vs {theirs.shape}")
a, b = ours < 1.0, theirs < 1.0
both = a & b
d = np.abs(ours - theirs)[both]
print(f"{ours.shape[1]}x{ours.shape[0]}: covered {a.sum()} (ours) / {b.sum()} (theirs); "
      f"coverage differs at {(a != b).sum()} px ({(a & ~b).sum()} only ours, {(b & ~a).sum()} only theirs); "
      f"identical depth at {(ours.astype(np.float32) == theirs.astype(np.float32)).sum()} of {ours.size} px; "
      f"|depth difference| where both cover: max {d.max() if d.size else 0:.3e}, mean {d.mean() if d.size else 0:.3e}")
