"""The closed-form figures of the papers and the comparisons they lack, as arrays.

``figure(name)`` returns what ``shadowlab curves`` writes to the figure's CSV, so a user redraws
it with matplotlib."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _native

__all__ = ["Figure", "figure", "NAMES"]

#: The figures (``shadowlab_curves::FigureName``).
NAMES = ("lispsm-fig6", "cad-fig7", "gmnpr-fig5", "gmnpr-fig6", "partitions", "max-error-vs-angle")


@dataclass(frozen=True)
class Figure:
    """A figure's data: its title and one float64 array per column of its table."""

    name: str
    title: str
    columns: dict[str, np.ndarray]


def figure(name: str, *, near: float = 1.0, far: float = 100.0, fov_degrees: float = 60.0) -> Figure:
    """The figure ``name`` (one of :data:`NAMES`) for the papers' configuration."""
    title, columns, rows = _native.figure(name, near=near, far=far, fov_degrees=fov_degrees)
    table = np.array(rows, dtype=np.float64).reshape(len(rows), len(columns))
    return Figure(name, title, {column: table[:, k].copy() for k, column in enumerate(columns)})
