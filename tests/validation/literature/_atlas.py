"""Shared by the literature modules: run one case of the atlas (tce.quality.validation.CASES)."""

from tce.quality.validation import CASES, run_validation


def check_case(name: str) -> float:
    """Compute the case ``name`` and assert it is within its stated tolerance of its reference
    and rounds (or not) to the published value as it states; return tce's value."""
    (case,) = [c for c in CASES if c.name == name]
    row = run_validation([case]).iloc[0]
    assert row["ok"], (f"{name}: tce {row['tce']!r} against {case.expected} (published {case.published}, "
                       f"{case.source}, {case.where}; at its digits {row['rounded']}): {case.why}")
    return float(row["tce"])
