"""A sweep's tables as a researcher reads them: `results.parquet` straight into pandas (pyarrow)
and polars, with the CSV's values, integer, float, boolean and text columns typed as such, and
nulls where a technique is not defined."""

import math
import subprocess

import pandas as pd
import polars as pl
import pytest

SPEC = """
scenes = ["outdoor", "room-point"]
techniques = ["psm"]
resolutions = [64, 128]
[lights]
kind = "gamma"
degrees = [5.0, 60.0]
"""


@pytest.fixture(scope="module")
def merged(tmp_path_factory, shadowlab_binary):
    root = tmp_path_factory.mktemp("sweep")
    spec = root / "spec.toml"
    spec.write_text(SPEC)
    subprocess.run([shadowlab_binary, "sweep", str(spec), "--out", str(root / "study")], check=True, capture_output=True)
    return root / "study" / "merged"


def test_pandas_reads_the_parquet_table_as_the_csv(merged):
    table = pd.read_parquet(merged / "results.parquet")
    csv = pd.read_csv(merged / "results.csv", keep_default_na=False, na_values=[""])
    assert list(table.columns) == list(csv.columns)
    assert len(table) == len(csv) == 8
    assert list(table["cell"]) == list(range(8))
    for column in ("cell", "resolution", "visible", "camera", "light"):
        assert table[column].dtype == "int64", column
    assert table["defined"].dtype == bool
    assert table["gamma_deg"].dtype == "float64"
    for column in table.columns:
        for a, b in zip(table[column], csv[column]):
            if isinstance(a, float) and math.isnan(a):
                assert isinstance(b, float) and math.isnan(b), column
            elif isinstance(a, float):
                # The CSV prints each f64 in its shortest round-trip form.
                assert a == float(b), column
            else:
                assert str(a) == str(b) or a == b, column


def test_polars_reads_the_parquet_table_with_nulls(merged):
    table = pl.read_parquet(merged / "results.parquet")
    assert table.schema["misclassified"] == pl.Int64
    assert table.schema["technique"] == pl.String
    assert table.schema["defined"] == pl.Boolean
    defined = table.filter(pl.col("defined"))
    assert defined["misclassified"].null_count() == 0
    undefined = table.filter(~pl.col("defined"))
    # PSM is not defined where room-point's light lies inside its focus body: both kinds occur.
    assert 0 < len(undefined) < len(table)
    assert undefined["misclassified"].null_count() == len(undefined)
    assert (undefined["undefined_reason"].null_count()) == 0
    assert table["scene"].unique().sort().to_list() == ["outdoor", "room-point"]
