"""Figures of an uncertainty study: what each draws is what results.nc holds.

The results are a real small study's (:func:`plot.uncertainty_data.small_study`) with the
layout's uncertainty variables added (:func:`plot.uncertainty_data.with_uncertainty`):
fragility curves, histograms, sensitivities and the running estimate are read back from the
drawn artists and compared with the dataset, the running estimate's end with the stored
failure probability. Every sample outcome word (all unbounded, all infeasible, all or some
numerical) must draw and be said in words; a study without ``[uncertainty]`` draws no new figure.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from plot.uncertainty_data import small_study, with_uncertainty
from tce.plot.data import UNCERTAINTY_KINDS, capacity_label, counts_note, plot_spec, settlement_parameter
from tce.plot.output import builder, figure_tasks, write_figures
from tce.plot.uncertainty import (
    MAX_CURVES,
    capacity_samples_figure,
    convergence_figure,
    fragility_figure,
    running_estimate,
    sensitivity_figure,
)

THIN, MID, THICK = "none/thickness=0.2", "none/thickness=0.25", "none/thickness=0.3"
#: scenarios ending their samples in each outcome word (tests/plot/uncertainty_data.py, MODES)
OUTCOMES = {
    "unbounded, infeasible, some numerical": {THIN: "infeasible", MID: "unbounded", THICK: "some_numerical"},
    "all numerical": {THIN: "numerical", THICK: "unbounded"},
}


@pytest.fixture(scope="module")
def base(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """The small study's results, without ``[uncertainty]``."""
    return small_study(tmp_path_factory.mktemp("uq"))


@pytest.fixture(scope="module")
def uq(base: xr.Dataset) -> xr.Dataset:
    return with_uncertainty(base, n=300)


def _gid(fig: Figure, gid: str) -> list:
    return [a for ax in fig.axes for a in ax.get_children() if a.get_gid() == gid]


def _words(fig: Figure) -> str:
    """Every text of a figure (titles, labels, legends), its line breaks folded."""
    texts = [t.get_text() for t in fig.texts]
    for ax in fig.axes:
        texts += [t.get_text() for t in ax.texts] + [ax.get_xlabel(), ax.get_ylabel(), ax.get_title(loc="left")]
        legend = ax.get_legend()
        texts += [t.get_text() for t in legend.get_texts()] if legend else []
    texts += [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    return " ".join(" ".join(texts).split())


def _png(fig: Figure) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=50)
    return buf.getvalue()


def test_a_study_without_uncertainty_draws_no_new_figure(base: xr.Dataset, uq: xr.Dataset, tmp_path: Path) -> None:
    """The uncertainty kinds are asked for in both; they are drawn only where the samples
    are. Without [plots] kinds, they are the default kinds only where the samples are (a
    study without [uncertainty] does not even say it does not draw them)."""
    kinds = {t.kind for t in figure_tasks(base, plot_spec(base))}
    assert kinds == {"summary"}
    assert not set(plot_spec(base.assign_attrs(study="")).kinds) & set(UNCERTAINTY_KINDS)
    assert set(plot_spec(uq.assign_attrs(study="")).kinds) >= set(UNCERTAINTY_KINDS)
    files = write_figures(uq, tmp_path, plot_spec(uq))
    assert sorted(p.name for p in files) == sorted(["summary.png", *(f"{k}.png" for k in UNCERTAINTY_KINDS)])
    assert all(p.stat().st_size > 0 for p in files)


def test_fragility_draws_the_stored_curves_and_the_sweep(uq: xr.Dataset) -> None:
    """Each curve is the stored P(capacity < x); the failure probability sits on the
    threshold; the sweep panel draws it against the thickness; the x label says what the
    capacity measures, and a settlement capacity says so."""
    fig = fragility_figure(uq)
    threshold = float(uq.attrs["uncertainty_threshold"])
    for s in uq["scenario"].values.tolist():
        (line,) = _gid(fig, f"fragility:{s}")
        np.testing.assert_array_equal(line.get_xdata(), uq["fragility_intensity"].sel(scenario=s).values)
        np.testing.assert_array_equal(line.get_ydata(), uq["fragility_probability"].sel(scenario=s).values)
        (pf,) = _gid(fig, f"pf:{s}")
        x, y = pf.get_data()
        assert (x[0], y[0]) == (threshold, float(uq["failure_probability"].sel(scenario=s)))
    (sweep,) = _gid(fig, "pf_sweep:thickness (m):0")
    x, y = sweep.get_data()
    np.testing.assert_array_equal(x, [0.2, 0.25, 0.3])
    np.testing.assert_array_equal(y, uq["failure_probability"].values)
    words = _words(fig)
    assert f"x: {capacity_label('lambda_max')}" in words and "thickness (m)" in words
    assert f"failure: capacity < {threshold:g}" in words
    assert "λ multiplies the lateral load" in words
    settled = uq.assign(capacity_kind=("scenario", ["settlement_capacity"] * 3))
    assert "x: the settlement magnitude (× the scenario's settlement vectors)" in _words(fragility_figure(settled))


def test_fragility_names_the_scenarios_it_leaves_out(base: xr.Dataset) -> None:
    """Beyond MAX_CURVES scenarios the curves of an even selection are drawn and the note
    says how many of how many."""
    many = xr.concat([base.isel(scenario=[0])] * (MAX_CURVES + 2), dim="scenario", data_vars="all")
    many = many.assign_coords(scenario=[f"s{k}" for k in range(MAX_CURVES + 2)],
                              thickness=("scenario", np.linspace(0.2, 0.3, MAX_CURVES + 2)))
    fig = fragility_figure(with_uncertainty(many, n=50))
    assert f"{MAX_CURVES} of {MAX_CURVES + 2} scenarios drawn" in _words(fig)
    assert sum(bool(_gid(fig, f"fragility:s{k}")) for k in range(MAX_CURVES + 2)) == MAX_CURVES


def test_histograms_count_every_sample(uq: xr.Dataset) -> None:
    """The bars hold every finite capacity and the legend counts those below the threshold."""
    fig = capacity_samples_figure(uq)
    threshold = float(uq.attrs["uncertainty_threshold"])
    for s in uq["scenario"].values.tolist():
        bars = _gid(fig, f"samples:{s}")
        v = uq["sample_capacity"].sel(scenario=s).values
        assert sum(b.get_height() for b in bars) == np.isfinite(v).sum() == 300
        assert f"finite: 300 ({int((v < threshold).sum())} below the threshold)" in _words(fig)


def test_sensitivity_bars_are_the_stored_values(uq: xr.Dataset) -> None:
    """One bar per variable and scenario, its length the stored sensitivity; FORM's alpha in
    a second panel only where it was computed; the method in the title."""
    fig = sensitivity_figure(uq)
    for s in uq["scenario"].values.tolist():
        widths = [b.get_width() for b in _gid(fig, f"sensitivity:{s}")]
        np.testing.assert_array_equal(widths, uq["sensitivity"].sel(scenario=s).values)
        np.testing.assert_array_equal([b.get_width() for b in _gid(fig, f"alpha:{s}")],
                                      uq["form_alpha"].sel(scenario=s).values)
    assert "Spearman rank correlation" in fig.get_suptitle()
    without = sensitivity_figure(uq.drop_vars([v for v in uq.data_vars if str(v).startswith("form_")]))
    assert len([ax for ax in without.axes if ax.get_visible()]) == 1
    assert not any(_gid(without, f"alpha:{s}") for s in uq["scenario"].values.tolist())


def test_running_estimate_ends_at_the_stored_probability(uq: xr.Dataset) -> None:
    """The running estimate of all N samples is the stored failure probability and its
    interval; FORM and subset estimates are horizontal lines at their stored values."""
    fig = convergence_figure(uq)
    threshold = float(uq.attrs["uncertainty_threshold"])
    for s in uq["scenario"].values.tolist():
        (line,) = _gid(fig, f"running:{s}")
        assert line.get_xdata()[-1] == 300
        assert line.get_ydata()[-1] == pytest.approx(float(uq["failure_probability"].sel(scenario=s)), rel=1e-12)
        ns, pf, lo, hi = running_estimate(uq["sample_capacity"].sel(scenario=s).values, threshold, 0.95,
                                          "clopper-pearson")
        assert (lo[-1], hi[-1]) == pytest.approx((float(uq["failure_low"].sel(scenario=s)),
                                                  float(uq["failure_high"].sel(scenario=s))), rel=1e-12)
        assert np.all(np.diff(ns) > 0) and ns[0] == 1
        for what in ("form", "subset"):
            (h,) = _gid(fig, f"{what}:{s}")
            assert h.get_ydata()[0] == float(uq[f"{what}_pf"].sel(scenario=s))


@pytest.mark.parametrize("variant", list(OUTCOMES))
@pytest.mark.parametrize("kind", UNCERTAINTY_KINDS)
def test_every_sample_outcome_draws_and_is_said(base: xr.Dataset, variant: str, kind: str) -> None:
    """Scenarios whose samples are all unbounded, all infeasible, all or some numerical:
    every figure draws (to PNG) and counts them in words."""
    modes = OUTCOMES[variant]
    ds = with_uncertainty(base, n=200, modes=modes)
    fig = builder(kind)(ds)
    assert _png(fig)
    words = _words(fig)
    if kind == "capacity_samples":  # the counts in each panel's legend
        for s, mode in modes.items():
            word = {"some_numerical": "numerical"}.get(mode, mode)
            n = 20 if mode == "some_numerical" else 200
            assert f"{word}: {n} (" in words, (s, words)
    else:
        for s in modes:
            assert f"{s}: {counts_note(ds, s)}" in words, (s, words)
    if "infeasible" in modes.values() and kind == "fragility":  # P = 1 at every x: a horizontal line
        (line,) = _gid(fig, f"fragility:{THIN}")
        assert list(line.get_ydata()) == [1.0, 1.0]
    if "numerical" in modes.values() and kind == "convergence":
        assert "no decided sample: no estimate" in words


def test_counts_note_words() -> None:
    """What the notes say of each outcome word, read on a dataset with every word."""
    words = [["unbounded"] * 4, ["optimal", "numerical", "infeasible", "numerical"]]
    ds = xr.Dataset({"sample_status": (("scenario", "sample"), words)}, coords={"scenario": ["a", "b"]})
    assert counts_note(ds, "a") == "all 4 samples unbounded: no finite limit (+inf: survives)"
    assert counts_note(ds, "b") == ("1 of 4 infeasible: nothing stands (-inf: fails); "
                                    "2 of 4 numerical: undecided (NaN: left out of the estimate)")


def _cases(uq: xr.Dataset, motions: dict[str, str]) -> xr.Dataset:
    """``uq`` as if its scenarios were the settlement cases ``motions`` (name -> the TOML of
    its table), nothing swept."""
    study = "".join(f"[scenarios.{c}]\n{m}\n" for c, m in motions.items())
    out = uq.drop_vars("thickness").assign_coords(scenario=list(motions), settlement=("scenario", list(motions)))
    return out.assign_attrs(study=study)


def test_settlement_cases_differing_in_one_number_are_a_sweep(uq: xr.Dataset) -> None:
    """Three cases that move the right support down by 1, 2 and 3 mm: the failure
    probability is drawn against that motion; cases that differ in two numbers are not a sweep."""
    ds = _cases(uq, {"a": "right = [0.0, 0.0, -0.001, 0.0, 0.0, 0.0]", "b": "right = [0.0, 0.0, -0.002, 0.0, 0.0, 0.0]",
                     "c": "right = [0.0, 0.0, -0.003, 0.0, 0.0, 0.0]\nleft = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]"})
    assert settlement_parameter(ds, ["a", "b", "c"]) == ("right uz (m)", {"a": -0.001, "b": -0.002, "c": -0.003})
    (sweep,) = _gid(fragility_figure(ds), "pf_sweep:settlement case: right uz (m):0")
    x, y = sweep.get_data()
    np.testing.assert_array_equal(x, [-0.003, -0.002, -0.001])
    np.testing.assert_array_equal(y, uq["failure_probability"].values[::-1])
    two = _cases(uq, {"a": "right = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0]", "b": "right = [0.0, 0.0, -0.002, 0.0, 0.0, 0.0]",
                      "c": "right = [0.0, 0.0, -0.003, 0.0, 0.0, 0.0]"})
    assert settlement_parameter(two, ["a", "b", "c"]) is None
    assert not any("pf_sweep" in str(a.get_gid()) for ax in fragility_figure(two).axes for a in ax.get_children())
