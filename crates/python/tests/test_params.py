"""The closed forms from Python: shapes, dtypes and broadcasting as numpy's, errors naming the
parameter, and the papers' claims restated as properties (hypothesis, derandomized)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from shadowlab import params

depths = st.tuples(
    st.floats(min_value=0.01, max_value=10.0), st.floats(min_value=1.5, max_value=1e4)
).map(lambda nf: (nf[0], nf[0] * nf[1]))
angles = st.floats(min_value=math.radians(5.0), max_value=math.radians(90.0))
half_fovs = st.floats(min_value=math.radians(5.0), max_value=math.radians(60.0))


def test_scalars_give_zero_dimensional_float64_arrays():
    out = params.lispsm_dp_ds(1.0, 100.0, 11.0, 5.0)
    assert isinstance(out, np.ndarray) and out.shape == () and out.dtype == np.float64


def test_arguments_broadcast_as_numpy_does():
    z = np.linspace(1.0, 100.0, 7)
    n = np.array([[2.0], [11.0], [np.inf]])
    out = params.lispsm_dp_ds(1.0, 100.0, n, z)
    assert out.shape == (3, 7)
    for i in range(3):
        for j in range(7):
            assert out[i, j] == params.lispsm_dp_ds(1.0, 100.0, n[i, 0], z[j])
    with pytest.raises(ValueError):
        params.lispsm_dp_ds(1.0, 100.0, np.ones(3), np.ones(4))


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: params.lispsm_dp_ds(1.0, 0.5, 2.0, 1.0), "far"),
        (lambda: params.lispsm_dp_ds(float("nan"), 100.0, 2.0, 1.0), "near"),
        (lambda: params.lispsm_dp_ds(1.0, 100.0, 2.0, 500.0), "z"),
        (lambda: params.lispsm_n_opt_general(1.0, 100.0, 2.0), "gamma"),
        (lambda: params.gmnpr_error(1.0, 100.0, math.radians(30), 0.5, -1.0, 10.0), "lambda"),
        (lambda: params.rule_lambda("glpr", 1.0, 100.0, math.radians(30), math.radians(10)), "gamma"),
        (lambda: params.rule_lambda("nope", 1.0, 100.0, 0.5, 0.5), "rule"),
        (lambda: params.cad_n_prime(1.0, 100.0, 0.5, 0.5, falloff="nope"), "falloff"),
        (lambda: params.split_boundaries("uniform", 1.0, 100.0, 0), "partitions"),
        (lambda: params.bias_z_map("midpoint", 0.5, 0.25), "z2"),
        (lambda: params.bias_z_map("dual-depth", 0.25, 0.75, -1.0), "max_bias"),
        (lambda: params.bias_z_map("slope", 0.25, 0.75), "method"),
    ],
)
def test_a_bad_value_raises_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError) as error:
        call()
    assert str(error.value).startswith(name), str(error.value)


@given(depths)
def test_lispsm_n_opt_equalises_the_error_at_near_and_far(nf):
    near, far = nf
    n = params.lispsm_n_opt(near, far)
    at_near, at_far = params.lispsm_dp_ds(near, far, n, [near, far])
    assert at_near == pytest.approx(at_far, rel=1e-9)


@given(depths, half_fovs, angles)
def test_the_equal_error_lambda_equalises_f_at_near_and_far(nf, half_fov, gamma):
    near, far = nf
    try:
        lam = params.gmnpr_lambda_equal_error(near, far, half_fov, gamma)
    except ValueError as error:
        assert str(error).startswith("gamma")
        return
    at_near, at_far = params.gmnpr_error(near, far, half_fov, gamma, lam, [near, far])
    assert at_near == pytest.approx(at_far, rel=1e-7)


@given(depths, st.floats(min_value=0.0, max_value=1.0))
def test_large_n_tends_to_the_uniform_map(nf, t):
    near, far = nf
    z = near + t * (far - near)
    uniform = params.lispsm_dp_ds(near, far, np.inf, z)
    large = params.lispsm_dp_ds(near, far, 1e9 * far, z)
    assert large == pytest.approx(uniform, rel=1e-6)


@given(depths, half_fovs, angles, st.floats(min_value=1e-3, max_value=0.2))
def test_the_minimax_rule_is_not_beaten_by_perturbing_it(nf, half_fov, gamma, step):
    near, far = nf
    lam = params.rule_lambda("minimax", near, far, half_fov, gamma)
    best = params.gmnpr_max_error(near, far, half_fov, gamma, lam)
    for other in (lam * (1 + step), lam / (1 + step)):
        assert params.gmnpr_max_error(near, far, half_fov, gamma, other) >= best * (1 - 1e-9)


@given(depths, half_fovs, angles)
def test_every_rule_gives_a_positive_lambda_where_defined(nf, half_fov, gamma):
    near, far = nf
    for rule in params.RULES:
        try:
            lam = params.rule_lambda(rule, near, far, half_fov, gamma)
        except ValueError as error:
            assert rule == "glpr" and str(error).startswith("gamma")
            continue
        assert lam > 0


def test_split_boundaries_run_from_near_to_far():
    for scheme in ("uniform", "logarithmic", "practical", "adaptive"):
        b = params.split_boundaries(scheme, 1.0, 100.0, 4)
        assert b.shape == (5,) and b[0] == 1.0 and b[-1] == 100.0 and np.all(np.diff(b) > 0)
    assert np.allclose(params.split_boundaries("logarithmic", 1.0, 100.0, 2), [1.0, 10.0, 100.0])


@given(st.floats(0.0, 1.0), st.floats(0.0, 0.1), st.floats(0.0, 1.0))
def test_vsm_is_a_fraction_and_lit_in_front(mean, variance, t):
    lit = params.vsm_lit_fraction(mean, variance, t)
    assert 0.0 <= lit <= 1.0
    if t <= mean:
        assert lit == 1.0


def test_the_depth_biases_of_table_1():
    z1, z2 = 0.25, 0.75
    assert params.bias_z_map("constant", z1, z2, 0.01) == pytest.approx(0.26)
    assert params.bias_z_map("second-depth", z1, z2) == z2
    assert params.bias_z_map("midpoint", z1, z2) == 0.5
    assert params.bias_z_map("dual-depth", z1, z2, 0.125) == 0.375
    assert params.bias_z_map("midpoint", z1, np.inf) == np.inf
