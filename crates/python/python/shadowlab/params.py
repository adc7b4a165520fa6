"""The closed forms and parameter rules of the five shadow-map papers, vectorised.

Every function takes numbers or array-likes, broadcasts them against each other as numpy does, and
returns a float64 array of the broadcast shape (a 0-d array for scalar inputs). Angles are in
radians. A value outside a formula's domain raises ``ValueError`` naming the parameter — the same
domains as the Rust types of ``shadowlab-params`` — never a silent NaN.

Sources: LiSPSM (Wimmer, Scherzer & Purgathofer, EGSR 2004), CAD (Lloyd, Tuft, Yoon & Manocha,
EGSR 2006 and TOG 2008), GMNPR (Zhang, Lloyd et al.), PSM (Stamminger & Drettakis 2002), VSM
(Donnelly & Lauritzen 2006); formulas.md in the project's shared docs reconstructs each.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from . import _native

__all__ = [
    "bias_z_map",
    "cad_m_z",
    "cad_n_prime",
    "gmnpr_error",
    "gmnpr_lambda_equal_error",
    "gmnpr_max_error",
    "lispsm_dp_ds",
    "lispsm_max_error",
    "lispsm_n_delta_z",
    "lispsm_n_opt",
    "lispsm_n_opt_general",
    "rule_lambda",
    "split_boundaries",
    "vsm_lit_fraction",
    "RULES",
    "FALLOFFS",
]

#: The parameter rules :func:`rule_lambda` knows (``shadowlab_params::ParameterRule``).
RULES = ("uniform", "lispsm", "lispsm_dz", "cad", "cad_eq17", "cad_sin2", "gmnpr", "glpr", "minimax")
#: CAD's fall-back curves r(γ) for :func:`cad_n_prime` (eqs. 17, 18 and sin²).
FALLOFFS = ("eq18", "eq17", "sin2")


ArrayLike = npt.ArrayLike
F64 = npt.NDArray[np.float64]


def _call(function, *arguments) -> F64:
    """``function`` of the broadcast arguments, flattened and reshaped back."""
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in arguments))
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
    return function(*flat).reshape(shape)


def lispsm_dp_ds(near: ArrayLike, far: ArrayLike, n: ArrayLike, z: ArrayLike) -> F64:
    """LiSPSM eq. 3: the perspective aliasing dp/ds at eye depth ``z`` for P's near distance ``n``
    (``n = inf`` is the uniform map), the view's depths ``near`` and ``far``."""
    return _call(_native.lispsm_dp_ds, near, far, n, z)


def lispsm_n_opt(near: ArrayLike, far: ArrayLike) -> F64:
    """LiSPSM §4.4: n_opt = near + √(far·near), the near distance that equalises dp/ds at near and
    far (the light perpendicular to the view)."""
    return _call(_native.lispsm_n_opt, near, far)


def lispsm_n_opt_general(near: ArrayLike, far: ArrayLike, gamma: ArrayLike) -> F64:
    """LiSPSM §4.4 at any light angle: n_opt = (near + √(far·near))/sin γ."""
    return _call(_native.lispsm_n_opt_general, near, far, gamma)


def lispsm_n_delta_z(z0: ArrayLike, depth: ArrayLike, gamma: ArrayLike) -> F64:
    """LiSPSM's Δz parameter: n = (z0 + √(z0 (z0 + depth·sin γ)))/sin γ."""
    return _call(_native.lispsm_n_delta_z, z0, depth, gamma)


def lispsm_max_error(near: ArrayLike, far: ArrayLike, n: ArrayLike) -> F64:
    """The largest dp/ds of LiSPSM eq. 3 over [near, far] for the near distance ``n``."""
    return _call(_native.lispsm_max_error, near, far, n)


def cad_m_z(near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike, n_prime: ArrayLike, z: ArrayLike, resolution_ratio: ArrayLike = 1.0) -> F64:
    """CAD eq. 12: the aliasing error m_z along the warp axis at eye depth ``z`` for P's near
    distance ``n_prime``, times the ratio of image to shadow-map resolution."""
    return _call(_native.cad_m_z, near, far, half_fov, gamma, n_prime, z, resolution_ratio)


def cad_n_prime(near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike, falloff: str = "eq18") -> F64:
    """CAD eq. 16: n′(γ) with the fall-back curve ``falloff`` (one of :data:`FALLOFFS`)."""
    return _call(lambda *a: _native.cad_n_prime(falloff, *a), near, far, half_fov, gamma)


def gmnpr_error(near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike, lam: ArrayLike, z: ArrayLike) -> F64:
    """GMNPR eqs. 1–2: the normalised perspective error F(λ, θ, z) (``lam = inf``: uniform)."""
    return _call(_native.gmnpr_error, near, far, half_fov, gamma, lam, z)


def gmnpr_lambda_equal_error(near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike) -> F64:
    """GMNPR eq. 4 (CAD eq. 13): the λ with F(λ, θ, near) = F(λ, θ, far). Below θ₀ none exists:
    ``ValueError`` naming ``gamma``."""
    return _call(_native.gmnpr_lambda_equal_error, near, far, half_fov, gamma)


def gmnpr_max_error(near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike, lam: ArrayLike) -> F64:
    """F's largest value over [near, far] (F is convex in z): max(F(near), F(far))."""
    return _call(_native.gmnpr_max_error, near, far, half_fov, gamma, lam)


def rule_lambda(rule: str, near: ArrayLike, far: ArrayLike, half_fov: ArrayLike, gamma: ArrayLike) -> F64:
    """The warp parameter λ that ``rule`` (one of :data:`RULES`) picks; ``inf`` for uniform.

    GLPR is defined for γ > φ only: an angle outside raises ``ValueError`` naming ``gamma``."""
    return _call(lambda *a: _native.rule_lambda(rule, *a), near, far, half_fov, gamma)


def split_boundaries(scheme: str, near: float, far: float, partitions: int, *, weight: float = 0.5, delta: float = 2.0, gamma: float = np.pi / 2) -> F64:
    """The ``partitions + 1`` boundaries of a z-partition of [near, far]: ``uniform``,
    ``logarithmic`` (CAD eq. 5), ``practical`` (Zhang et al., ``weight``) or ``adaptive`` (CAD
    eq. 19, ``delta`` at the light angle ``gamma``)."""
    return _native.split_boundaries(
        scheme, float(near), float(far), int(partitions), weight=float(weight), delta=float(delta), gamma=float(gamma)
    )


def bias_z_map(method: str, z1: ArrayLike, z2: ArrayLike, amount: ArrayLike = 0.0) -> F64:
    """The CAD survey's eq. 1 and Table 1: z_map = z1 + z_bias(z1, z2) for the depth bias
    ``method`` — ``constant`` (``amount`` its offset), ``second-depth``, ``midpoint``, ``dual-depth``
    (``amount`` its cap) — of the first and second surfaces' depths (``z2 = inf``: none behind)."""
    return _call(lambda *a: _native.bias_z_map(method, *a), z1, z2, amount)


def vsm_lit_fraction(mean: ArrayLike, variance: ArrayLike, t: ArrayLike, min_variance: ArrayLike = 1e-6) -> F64:
    """VSM (CAD survey eq. 2): the Chebyshev upper bound on the lit fraction at receiver depth
    ``t`` of depths with this mean and variance (the variance floored at ``min_variance``)."""
    return _call(_native.vsm_lit_fraction, mean, variance, t, min_variance)
