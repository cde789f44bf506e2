"""Interface material: friction, cohesion, tensile and compressive strength, flow rule, stiffness.

The contact law of one contact (a vertex of an interface, or a planar contact standing for
the vertices that project onto it) with tributary area ``A`` (m^2), normal force ``fn``
(kN, positive in compression) and tangential force ``ft`` (kN)::

    -t A  <=  fn  <=  fc A                    (tension cut-off, crushing)
    ||ft||  <=  mu fn + c A                   (Mohr-Coulomb; mu = None: no limit)

with ``c`` the cohesion, ``t`` the tensile strength and ``fc`` the compressive strength
(kN/m^2). The defaults (``c = t = 0``, ``fc`` None) are the paper's dry joint: no tension,
Coulomb friction, unlimited compressive strength. The rows of this law are built by
:func:`tce.core.conic.cone_rows`; ``docs/materials.md`` says what each parameter means and
where the model stops.

What the parameters mean at the ends of the friction range:

- ``friction = 0`` with cohesion: a purely cohesive (Tresca) joint, ``||ft|| <= c A``
  whatever the normal force;
- ``friction = None`` (Heyman: unlimited friction) has no sliding limit for cohesion to
  raise, so a cohesion with it is refused (an option with no effect);
- with ``friction > 0`` the Mohr-Coulomb cone itself caps tension at ``fn >= -(c/mu) A``
  (its apex): a tensile strength above ``c / mu`` could never be reached and is refused.

Per-interface laws: an interface carries a ``kind`` (a label, ``""`` by default:
:class:`tce.structures.assembly.Interface`), and a material may give a kind its own law
(``Material(friction=0.6, interfaces={"ring": Material(friction=0.5)})``: the joints between
the rings of a multi-ring arch). Every interface of another kind keeps the material's own law.
A kind's law carries friction and strengths only (stiffness and flow rule are the material's);
``bonded=True`` is a law that carries any tension and shear (two blocks glued: no row at all).
:meth:`Material.contact_law` gives the parameters of every contact of a model.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["FLOWS", "Material"]

#: flow rules of the friction law: ``associative`` (the limit theorems' normality, sliding
#: with dilatancy) or ``non-associative`` (sliding without opening; :mod:`tce.analysis.nonassoc`)
FLOWS = ("associative", "non-associative")


def _finite(name: str, value: float | None, lower: float, strict: bool) -> None:
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number (float), got {type(value).__name__} {value!r}")
    v = float(value)
    if not math.isfinite(v) or v < lower or (strict and v == lower):
        bound = f"> {lower}" if strict else f">= {lower}"
        raise ValueError(f"{name} must be a finite number {bound}, got {value!r}")


@dataclass(frozen=True)
class Material:
    """Contact law of the interfaces (see module docstring).

    Parameters
    ----------
    friction : float or None
        Coulomb friction coefficient mu >= 0 (``||ft|| <= mu fn + c A`` per contact vertex);
        ``None`` is a Heyman material with unlimited friction.
    normal_stiffness : float or None
        Normal stiffness per unit area (kN/m^3). ``None`` is the rigid case (``D = 0``).
    shear_stiffness : float or None
        Tangential stiffness per unit area (kN/m^3); defaults to ``normal_stiffness``.
        Only meaningful with a normal stiffness.
    cohesion : float
        Cohesion ``c`` >= 0 (kN/m^2): shear capacity per unit area at zero normal force.
        Needs a friction coefficient (not Heyman).
    tensile_strength : float
        Tensile strength ``t`` >= 0 (kN/m^2): ``fn >= -t A``. With ``friction > 0`` at most
        ``cohesion / friction`` (the apex of the Mohr-Coulomb cone).
    compressive_strength : float or None
        Compressive strength ``fc`` > 0 (kN/m^2): ``fn <= fc A`` at every contact vertex;
        ``None`` is unlimited.
    flow : {"associative", "non-associative"}
        Flow rule of the friction law. The static problems (TCE, load path, the direct
        limit) are the same for both; ``non-associative`` adds the iterative estimate of
        :func:`tce.analysis.nonassoc.nonassociative_limit` wherever a limit is reported.
    bonded : bool
        True: a contact that carries any tension and shear (two blocks glued together, no
        contact law at all); then friction, cohesion and strengths must be left out. Meant
        for an interface kind (``interfaces``), e.g. rings that cannot separate.
    interfaces : mapping of str to Material
        The law of each interface kind (:attr:`tce.structures.assembly.Interface.kind`) that
        does not follow this material's own; each is a Material without stiffness, flow rule
        or laws of its own. Stored as a tuple of ``(kind, Material)`` pairs sorted by kind.

    Raises
    ------
    ValueError
        A negative, NaN or infinite parameter, an unknown ``flow``, a cohesion with
        unlimited friction, a tensile strength above ``cohesion / friction``, or a shear
        stiffness without a normal one, a bonded law with friction or strengths, an
        interface law with stiffness, flow rule or laws of its own, or interface laws with
        the non-associative flow. The message names the parameter.
    TypeError
        A parameter that is not a real number (the string ``"0.8"``, a bool); the message
        names the parameter and the type expected.
    """

    friction: float | None = None
    normal_stiffness: float | None = None
    shear_stiffness: float | None = None
    cohesion: float = 0.0
    tensile_strength: float = 0.0
    compressive_strength: float | None = None
    flow: str = "associative"
    bonded: bool = False
    interfaces: Mapping[str, Material] | tuple[tuple[str, Material], ...] = ()

    def __post_init__(self) -> None:
        laws = dict(self.interfaces)
        for kind, law in laws.items():
            if not isinstance(kind, str) or not kind or not isinstance(law, Material):
                raise TypeError(f"interfaces must map interface kinds (non-empty str) to Materials, got {kind!r}: {law!r}")
            if not law.rigid or law.flow != "associative" or law.interfaces:
                raise ValueError(f"interfaces[{kind!r}]: an interface law gives friction and strengths only "
                                 "(stiffness, flow rule and laws of kinds are the material's)")
        if laws and self.flow != "associative":
            raise ValueError("interface laws with the non-associative flow are not supported: use flow = 'associative'")
        object.__setattr__(self, "interfaces", tuple(sorted(laws.items())))
        if self.bonded and (self.friction is not None or self.cohesion or self.tensile_strength
                            or self.compressive_strength is not None):
            raise ValueError("bonded: a bonded contact carries any force; leave friction, cohesion and strengths out")
        _finite("friction", self.friction, 0.0, strict=False)
        _finite("normal_stiffness", self.normal_stiffness, 0.0, strict=True)
        _finite("shear_stiffness", self.shear_stiffness, 0.0, strict=True)
        _finite("cohesion", self.cohesion, 0.0, strict=False)
        _finite("tensile_strength", self.tensile_strength, 0.0, strict=False)
        _finite("compressive_strength", self.compressive_strength, 0.0, strict=True)
        if self.flow not in FLOWS:
            raise ValueError(f"flow must be one of {list(FLOWS)}, got {self.flow!r}")
        if self.shear_stiffness is not None and self.normal_stiffness is None:
            raise ValueError("shear_stiffness needs a normal_stiffness (the rigid case has neither)")
        if self.normal_stiffness is not None and self.shear_stiffness is None:
            object.__setattr__(self, "shear_stiffness", self.normal_stiffness)
        for name in ("cohesion", "tensile_strength"):
            object.__setattr__(self, name, float(getattr(self, name)))
        if self.cohesion > 0 and self.friction is None:
            raise ValueError(
                "cohesion needs a friction coefficient: with friction absent (Heyman) sliding is "
                "never limited, so a cohesion would have no effect"
            )
        mu = self.friction
        if mu is not None and mu > 0 and self.tensile_strength > self.cohesion / mu * (1 + 1e-12):
            raise ValueError(
                f"tensile_strength {self.tensile_strength:g} exceeds cohesion / friction = "
                f"{self.cohesion / mu:g} kN/m^2, the tension at the apex of the Mohr-Coulomb cone: "
                "lower it or raise the cohesion"
            )

    @property
    def rigid(self) -> bool:
        """True when the contacts are rigid (no compliance term)."""
        return self.normal_stiffness is None

    @property
    def heyman(self) -> bool:
        """True when friction is unlimited."""
        return self.friction is None

    @property
    def strengths(self) -> dict[str, Any]:
        """``cohesion``, ``tensile_strength`` and ``compressive_strength`` as keyword arguments
        of :func:`tce.core.conic.cone_rows` and :func:`tce.core.conic.cone_violation`."""
        return {
            "cohesion": self.cohesion,
            "tensile_strength": self.tensile_strength,
            "compressive_strength": self.compressive_strength,
        }

    def law(self, kind: str) -> Material:
        """The law of the interfaces of ``kind``: its own when :attr:`interfaces` gives one,
        this material otherwise."""
        return dict(self.interfaces).get(kind, self)

    def contact_law(self, kinds: ArrayLike) -> dict[str, Any]:
        """The law of every contact as keyword arguments of :func:`tce.core.conic.cone_rows`
        and :class:`tce.core.conic.LawCheck`: ``friction``, ``cohesion``,
        ``tensile_strength`` and ``compressive_strength``.

        Parameters
        ----------
        kinds : (nc,) array_like of str
            The interface kind of each contact (:attr:`tce.core.model.Model.contact_kind`).

        Returns
        -------
        dict
            The material's own scalars (:attr:`strengths` and its friction) when no contact
            has a law of its own; otherwise ``(nc,)`` arrays with NaN friction for unlimited
            friction (Heyman), ``inf`` compressive strength for unlimited compression and
            ``inf`` tensile strength (with NaN friction) for a bonded contact (kN/m^2).
        """
        kinds = np.asarray(kinds, dtype=object)
        own = [(k, law) for k, law in self.interfaces if np.any(kinds == k)]
        if not own:
            return {"friction": self.friction, **self.strengths}
        mu, c, t, fc = (np.empty(len(kinds)) for _ in range(4))
        for law, at in [(self, ~np.isin(kinds, [k for k, _ in own]))] + [(law, kinds == k) for k, law in own]:
            mu[at] = np.nan if law.friction is None else law.friction
            c[at] = law.cohesion
            t[at] = np.inf if law.bonded else law.tensile_strength
            fc[at] = np.inf if law.compressive_strength is None else law.compressive_strength
        return {"friction": mu, "cohesion": c, "tensile_strength": t, "compressive_strength": fc}

    def describe(self) -> str:
        """The contact law in words, e.g. ``Coulomb friction mu = 0.8, no tension, unlimited
        compression, rigid contacts, associative flow`` (units kN, m); each interface kind
        with its own law follows as ``; "ring" interfaces: ...``."""
        own = "".join(f'; "{kind}" interfaces: {law._words(joint=True)}' for kind, law in self.interfaces)
        return self._words() + own

    def _words(self, joint: bool = False) -> str:
        """:meth:`describe` of this law alone; ``joint``: an interface kind's law, without the
        stiffness and flow rule (the material's)."""
        if self.bonded:
            return "bonded: any tension and shear carried"
        parts = ["Heyman: unlimited friction" if self.heyman else f"Coulomb friction mu = {self.friction:g}"]
        if self.cohesion:
            parts.append(f"cohesion {self.cohesion:g} kN/m^2")
        parts.append(f"tensile strength {self.tensile_strength:g} kN/m^2" if self.tensile_strength else "no tension")
        parts.append("unlimited compression" if self.compressive_strength is None
                     else f"compressive strength {self.compressive_strength:g} kN/m^2")
        if joint:
            return ", ".join(parts)
        parts.append("rigid contacts" if self.rigid else
                     f"compliant contacts (kn {self.normal_stiffness:g}, ks {self.shear_stiffness:g} kN/m^3)")
        if not self.heyman:
            parts.append(f"{self.flow} flow")
        return ", ".join(parts)

    @property
    def plain(self) -> bool:
        """True for the paper's dry joint: no cohesion, no tension, unlimited compression
        (and no interface kind with a law of its own)."""
        return (self.cohesion == 0 and self.tensile_strength == 0 and self.compressive_strength is None
                and not self.interfaces)
