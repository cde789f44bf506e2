"""``tce check``: run the hard cases (:mod:`tce.quality.hard`) and report a stability table."""

from __future__ import annotations

import argparse
from collections.abc import Sequence

import pandas as pd

from ..study.progress import track
from .hard import CASES, HardCase, run_case

__all__ = ["check_command", "format_table", "run_checks", "validation_command"]

COLUMNS = ["case", "expected", "status", "residual", "retry", "solves", "time_s", "ok", "errors"]


def run_checks(cases: Sequence[HardCase] = CASES, select: str | None = None) -> pd.DataFrame:
    """Run the hard cases and tabulate them.

    Parameters
    ----------
    cases : sequence of HardCase
    select : str, optional
        Run only the cases whose name contains this text (case-insensitive).

    Returns
    -------
    pandas.DataFrame
        One row per case: ``case``, ``expected`` and ``status`` (statuses joined by ``|``),
        ``residual`` (largest over the optimal solves), ``retry`` (what decided when
        Clarabel's first answer was not clean; empty if nothing), ``solves``, ``time_s``
        (wall time, s), ``ok`` and ``errors``.
    """
    rows = []
    chosen = [case for case in cases if not select or select.lower() in case.name.lower()]
    for case in track(chosen, "hard cases", unit="case", label=lambda c: c.name):
        run = run_case(case)
        rows.append({"case": case.name, "expected": "|".join(case.expected), "status": "|".join(run.statuses),
                     "residual": run.residual, "retry": ", ".join(run.retries), "solves": run.n_solves,
                     "time_s": run.time, "ok": run.ok, "errors": "; ".join(run.errors)})
    return pd.DataFrame(rows, columns=COLUMNS)


def format_table(table: pd.DataFrame) -> str:
    """The table as plain text (residuals in %.1e, times in %.3f s)."""
    return table.to_string(index=False, formatters={"residual": "{:.1e}".format, "time_s": "{:.3f}".format},
                           justify="left")


def check_command(args: argparse.Namespace | None = None) -> int:
    """Run the hard cases, print the table, and return 0 if every case passed (1 otherwise).

    ``args.select`` (optional) restricts the run to the cases whose name contains it;
    ``args.validation`` runs the validation atlas (:mod:`tce.quality.validation`) instead.
    """
    select = getattr(args, "select", None) if args is not None else None
    if getattr(args, "validation", False):
        return validation_command(select)
    table = run_checks(select=select)
    print(format_table(table.drop(columns="errors")))
    failed = table[~table["ok"]]
    for _, row in failed.iterrows():
        print(f"FAILED {row['case']}: {row['errors']}")
    print(f"{len(table) - len(failed)}/{len(table)} cases passed in {table['time_s'].sum():.1f} s")
    return 0 if failed.empty else 1


def validation_command(select: str | None = None) -> int:
    """Compute the validation cases (those whose name contains ``select``), print the table
    and return 0 if every case is within its tolerance (1 otherwise)."""
    from .validation import format_validation, run_validation

    table = run_validation(select=select)
    print(format_validation(table))
    failed = table[~table["ok"]]
    for _, row in failed.iterrows():
        print(f"FAILED {row['case']}: tce {row['tce']:.6g} against {row['published']:.6g} ({row['source']}, "
              f"{row['where']}), tolerance {row['tolerance']:.1e}")
    print(f"{len(table) - len(failed)}/{len(table)} cases within tolerance in {table['time_s'].sum():.1f} s "
          "(sources and convergence: docs/validation.md)")
    return 0 if failed.empty else 1
