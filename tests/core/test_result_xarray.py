"""The yes/no headline values of a result keep their sense in ``to_xarray`` (an attr, 1 for
True, 0 for False, "" for undecided): uniqueness decided both ways (issue 26, issue 21)."""

from __future__ import annotations

from helpers import block_on_support

from tce.core.analysis import Analysis
from tce.core.material import Material


def test_uniqueness_is_written_as_decided() -> None:
    an = Analysis(block_on_support(b=0.4, h=1.0), Material(friction=0.8))
    lim = an.limit(0.0).lambda_max
    at, inside = an.solve(lim * (1 - 1e-12), 0.0), an.solve(0.1, 0.0)
    assert (at.unique, inside.unique) == (True, False)
    assert (at.to_xarray().attrs["unique"], inside.to_xarray().attrs["unique"]) == (1, 0)
