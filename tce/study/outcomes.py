"""The words of a load path's outcome, as ``docs/conventions.md`` defines them, in one place.

Figure captions, the interactive view and ``tce show`` word outcomes with
:func:`outcome_words`: ``unbounded`` (admissible states exist, but the support motion is
incompatible with the material: the energy has no minimum) is not ``infeasible`` (no
admissible state), and ``no_limit`` (the direct limit is unbounded: the live loads are
carried at any multiplier) is not ``capped`` (the path stopped at a cap below a finite
collapse load).
"""

from __future__ import annotations

import math

__all__ = ["OUTCOME_MEANING", "STATUS_MEANING", "outcome_words", "status_words"]

#: what the status of one solve (one step of a load path) means
STATUS_MEANING = {
    "optimal": "",
    "infeasible": "infeasible: no admissible state at this {lam} (beyond the limit)",
    "unbounded": "unbounded: the support motion is incompatible with the material (no state of finite energy)",
    "numerical": "numerical: the solver could not decide this step",
}

#: what each outcome of a load path means (``{lam}`` is the multiplier's symbol)
OUTCOME_MEANING = {
    "limit": "",
    "capped": "at {lam} = {cap:.6g}, below the collapse load {lam}_direct = {direct:.6g}",
    "no_limit": "the direct limit is unbounded, the live loads are carried at any {lam}",
    "unbounded": "admissible states exist, but the support motion is incompatible with the material, "
                 "so the complementary energy has no minimum (no state of finite energy)",
    "infeasible": "no admissible state, not even at {lam} = 0",
    "numerical": "the solver could not decide the limit",
}
#: how an outcome is named before its meaning
_LABEL = {"capped": "capped", "no_limit": "no limit"}


def outcome_words(
    outcome: str,
    direct: float = math.nan,
    cap: float | None = None,
    reason: str = "",
    lam: str = "lambda",
    label: bool = True,
) -> str:
    """What a reader must know about an outcome ("" for ``limit``).

    Parameters
    ----------
    outcome : str
        ``limit``, ``capped``, ``no_limit``, ``unbounded``, ``infeasible`` or ``numerical``
        (another word is returned as it is).
    direct : float
        The direct lambda_max (for ``capped``).
    cap : float, optional
        The study's ``lambda_cap`` (for ``capped``).
    reason : str
        The explanation stored with the outcome (``no_limit_reason``, ``unbounded_reason``),
        appended after a colon.
    lam : str
        The multiplier's symbol: ``"lambda"`` in text, ``"λ"`` in figures.
    label : bool
        Start with the outcome's name (``"unbounded: admissible states exist, ..."``, and
        ``"capped at ..."``).
    """
    if outcome not in OUTCOME_MEANING:
        return outcome
    if not OUTCOME_MEANING[outcome]:
        return ""
    words = OUTCOME_MEANING[outcome].format(lam=lam, cap=math.nan if cap is None else cap, direct=direct)
    if label:
        name = _LABEL.get(outcome, outcome)
        words = f"{name} {words}" if outcome == "capped" else f"{name}: {words}"
    return f"{words}: {reason}" if reason else words


def status_words(status: str, lam: str = "lambda", at: float | None = None) -> str:
    """What the status of one solve means ("" for ``optimal``; another word as it is); ``at``:
    the step's multiplier (an infeasible step at 0 is not beyond a limit: nothing stands)."""
    if status == "infeasible" and at == 0:
        return f"infeasible: no admissible state even at {lam} = 0 (the structure cannot stand under its fixed loads)"
    return STATUS_MEANING[status].format(lam=lam) if status in STATUS_MEANING else status
