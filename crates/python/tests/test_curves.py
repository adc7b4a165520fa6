"""The figures' data from Python: what `shadowlab curves` writes, as arrays."""

import numpy as np
import pytest

from shadowlab import curves


@pytest.mark.parametrize("name", curves.NAMES)
def test_every_figure_has_columns_of_one_length(name):
    figure = curves.figure(name)
    lengths = {len(c) for c in figure.columns.values()}
    assert figure.title and len(figure.columns) >= 2 and len(lengths) == 1
    assert all(c.dtype == np.float64 for c in figure.columns.values())


def test_lispsm_fig6_matches_the_closed_form():
    from shadowlab import params

    f = curves.figure("lispsm-fig6")
    z = f.columns["z"]
    n = params.lispsm_n_opt(1.0, 100.0)
    assert np.allclose(f.columns["lispsm_n_opt"], params.lispsm_dp_ds(1.0, 100.0, n, z), rtol=1e-12)


def test_an_unknown_figure_names_the_parameter():
    with pytest.raises(ValueError, match="^name"):
        curves.figure("fig99")
