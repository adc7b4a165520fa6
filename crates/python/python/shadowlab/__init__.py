"""shadowlab from Python: shadow-map aliasing measured exactly, with numpy arrays in and out.

The package wraps the Rust crates of the shadowlab workspace (``shadowlab._native``):

* :mod:`shadowlab.params` — every closed form and parameter rule of the five papers, vectorised;
* :mod:`shadowlab.curves` — the closed-form figures as arrays;
* :class:`Scene` — a built-in scene, a TOML or glTF file, or arrays;
* :func:`plan`, :func:`render_map`, :func:`eye_pass`, :func:`truth`, :func:`analyze` — what the
  command-line tool computes, the same bits, as arrays and records.

Every long call releases the GIL. Images have row 0 at the bottom, as every shadowlab image.
"""

from __future__ import annotations

import json
from typing import Any, Optional, Sequence

from . import curves, params
from ._native import Scene
from ._native import __version__ as __version__
from ._native import analyze as _analyze
from ._native import eye_pass, plan, render_map, truth

__all__ = ["Analysis", "Scene", "analyze", "curves", "eye_pass", "params", "plan", "render_map", "truth"]


class Analysis:
    """A whole analysis: ``results`` is the document ``shadowlab analyze`` writes to
    ``results.json``; ``records`` one flat dict per combination, which ``pandas.DataFrame(...)``
    takes as it is (nested keys joined by ``_``: ``footprint_total_p99``, ``ms_total``).

    ``pixels`` (with ``analyze(..., pixels=True)``) maps each combination, keyed as its record's
    ``(setting_technique, setting_resolution, setting_maps, setting_filter)``, to its per-pixel
    arrays: ``lit``, each light's lit fraction (lights × H × W, 1 where nothing is seen), and
    ``footprint``, the texel footprint in pixels per texel (H × W, NaN where nothing is seen or
    the map has no derivative there); row 0 at the bottom."""

    def __init__(self, results: dict[str, Any], pixels: Sequence[tuple] = ()):
        self.results = results
        self.records = [_flat(m) for m in results["measurements"]]
        self.pixels = {
            (technique, resolution, maps, filter_): {"lit": lit, "footprint": footprint}
            for technique, resolution, maps, filter_, lit, footprint in pixels
        }

    def __repr__(self) -> str:
        return f"Analysis({self.results['scene']!r}: {len(self.records)} combinations)"


def _flat(value: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, item in value.items():
        name = f"{prefix}{key}"
        if isinstance(item, dict):
            out.update(_flat(item, f"{name}_"))
        else:
            out[name] = item
    return out


def analyze(
    scene: Scene,
    techniques: Optional[Sequence[str]] = None,
    resolutions: Optional[Sequence[int]] = None,
    partitions: Optional[Sequence[int]] = None,
    filters: Optional[Sequence[str]] = None,
    *,
    splits: str = "practical:0.5",
    bias: str = "slope:2,1e-5",
    focus: str = "light",
    timing_runs: int = 3,
    pixels: bool = False,
) -> Analysis:
    """Every combination of ``techniques`` (default: ``shadowlab analyze``'s for the scene's
    lights), ``resolutions`` (default 750–2000), ``partitions`` (default 1) and ``filters``
    (default ``nearest``), measured against the exact truth, as ``shadowlab analyze`` measures
    them; technique and filter specs are the command line's (``lispsm:minimax``, ``pcf:3``).
    With ``pixels``, every combination's per-pixel arrays are kept too (:class:`Analysis`)."""
    text, arrays = _analyze(
        scene,
        techniques=None if techniques is None else list(techniques),
        resolutions=None if resolutions is None else [int(r) for r in resolutions],
        partitions=None if partitions is None else [int(p) for p in partitions],
        filters=None if filters is None else list(filters),
        splits=splits,
        bias=bias,
        focus=focus,
        timing_runs=int(timing_runs),
        pixels=bool(pixels),
    )
    return Analysis(json.loads(text), arrays)
