"""shadowlab from Python, end to end: LiSPSM's Fig. 6 and the largest error against the light
angle redrawn with matplotlib from the library's arrays, and the default scene analyzed into a
pandas DataFrame.

    pip install ./crates/python matplotlib pandas
    python examples/python/aliasing.py OUT_DIR

Writes OUT_DIR/lispsm-fig6.png, OUT_DIR/max-error-vs-angle.png, OUT_DIR/outdoor.csv and
OUT_DIR/misclassified.png, and prints the DataFrame's best rows.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless: files only
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import shadowlab as sl  # noqa: E402
from shadowlab import curves, params  # noqa: E402


def lispsm_fig6(out: Path) -> None:
    """LiSPSM Fig. 6: dp/ds along the view axis, light perpendicular to the view, n = 1, f = 100 —
    computed here from the closed form, and checked against the library's own figure table."""
    near, far = 1.0, 100.0
    z = np.geomspace(near, far, 400)
    n_opt = params.lispsm_n_opt(near, far)
    table = curves.figure("lispsm-fig6")
    assert np.allclose(table.columns["lispsm_n_opt"], params.lispsm_dp_ds(near, far, n_opt, table.columns["z"]))
    fig, ax = plt.subplots(figsize=(6, 4))
    for n, label in [(np.inf, "uniform (n = ∞)"), (n_opt, f"LiSPSM n_opt = {float(n_opt):.1f}"), (near, "PSM-like (n = near)")]:
        ax.plot(z, params.lispsm_dp_ds(near, far, n, z), label=label)
    ax.set(xscale="log", yscale="log", xlabel="eye depth z", ylabel="dp/ds", title=table.title)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "lispsm-fig6.png", dpi=120)
    plt.close(fig)


def max_error_vs_angle(out: Path) -> None:
    """The largest perspective error over the view's depths against the light angle, per rule
    (GMNPR's F, the 60° view, n = 1, f = 100)."""
    near, far, half_fov = 1.0, 100.0, np.radians(30.0)
    gamma = np.radians(np.linspace(1.0, 90.0, 180))
    fig, ax = plt.subplots(figsize=(6, 4))
    for rule in ("uniform", "lispsm", "gmnpr", "minimax"):
        lam = params.rule_lambda(rule, near, far, half_fov, gamma)
        ax.plot(np.degrees(gamma), params.gmnpr_max_error(near, far, half_fov, gamma, lam), label=rule)
    ax.set(yscale="log", xlabel="γ, light–view angle (degrees)", ylabel="max F over [n, f]")
    ax.set_title("The largest error against the light angle")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "max-error-vs-angle.png", dpi=120)
    plt.close(fig)


def analyze_default_scene(out: Path) -> pd.DataFrame:
    """The default scene, four techniques at three map sides, into a DataFrame."""
    scene = sl.Scene.builtin("outdoor")
    analysis = sl.analyze(scene, ["uniform", "psm", "lispsm", "logarithmic"], [512, 1024, 2048], timing_runs=1)
    frame = pd.DataFrame(analysis.records)
    frame.to_csv(out / "outdoor.csv", index=False)
    fig, ax = plt.subplots(figsize=(6, 4))
    for technique, rows in frame.groupby("setting_technique"):
        ax.plot(rows["setting_resolution"], rows["misclassified"], marker="o", label=technique)
    ax.set(xscale="log", yscale="log", xlabel="shadow-map side (texels)", ylabel="misclassified pixels")
    ax.set_title(f"{scene.name}: misclassified pixels against the exact truth")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "misclassified.png", dpi=120)
    plt.close(fig)
    return frame


def main() -> None:
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/python")
    out.mkdir(parents=True, exist_ok=True)
    lispsm_fig6(out)
    max_error_vs_angle(out)
    frame = analyze_default_scene(out)
    columns = ["setting_technique", "setting_resolution", "misclassified", "footprint_total_p99"]
    print(frame.sort_values("misclassified")[columns].head(4).to_string(index=False))


if __name__ == "__main__":
    main()
