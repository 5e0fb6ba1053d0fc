"""The one place that prepares a mechanism from an arch.

"Which hinges does this arch have" has one answer, `archquake.limit.hinges_of`: those of the equivalent
static analysis (`archquake.limit.limit_analysis`, the paper's assumption), oriented so that
a ground acceleration towards -x opens them (the paper's Figure 1). `PreparedMechanism`
packs that mechanism for the compiled kernels (`pack_mechanism`) with its impact solution
(Eq. 4), once, and is what the time histories (`archquake.mechanism.simulate`), the domain
search (`archquake.domains`), the thrust line in motion (`archquake.thrust`) and the
distinct-element assemblies (`archquake.blocks.assembly`) all start from.

Its properties are the mechanism's scalar characteristics, so that no code outside
`archquake.mechanism` reads the packed layout:

* `PreparedMechanism.collapse_acceleration_g`: lambda, the equivalent static collapse
  acceleration in g (the onset threshold of hinging);
* `PreparedMechanism.critical_rotation`: the crest of the potential, rad;
* `PreparedMechanism.toggle_rotation`: the toggle of the linkage, rad;
* `PreparedMechanism.restitution`: the c_v the time histories use.

`PreparedMechanism.table` is the set of mechanisms the time history may move on under the
impact law, with its impact table (`ImpactTable`): for ``"paper"`` and ``"mirror"`` the
first mechanism alone (its mirror image is the same packed row on the other side), for
``"chain"`` every mechanism the law's post-impact map reaches from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch  # noqa: F401  (doctests)
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import HingeMechanism
from archquake.limit.analysis import hinges_of
from archquake.mechanism._kernels import Table, linkage_limits_compiled
from archquake.mechanism.impact import (
    ImpactSolution,
    check_impact_law,
    check_restitution,
    solve_impact,
)
from archquake.mechanism.kinematics import (
    AX,
    AY,
    B0X,
    B0Y,
    BRANCH,
    C0X,
    C0Y,
    DX,
    DY,
    G0,
    H0,
    LBC,
    LCD,
    LENGTH,
    LINK0,
    MASS,
    PACKED_SIZE,
    PHI_CRIT,
    PHI_TOGGLE,
    SIGMA,
    eom_terms,
)

#: Most mechanisms of a reachable set (`ImpactTable`); an impact whose post-impact
#: mechanism would be the next one is flagged (validity ``beyond_set``), never extrapolated.
MAX_REACHABLE = 32

#: The impact law a history uses when none is given: the one place the default is stated.
DEFAULT_IMPACT_LAW = "paper"

#: Validity of a row's impact beyond the chain laws' (`VALIDITY`
#: and Eq. 4's ``assumed``): the post-impact mechanism is not in the tabulated set.
BEYOND_SET = "beyond_set"

#: Samples of the crest/toggle search (`archquake.mechanism.kinematics.linkage_limits`).
_LIMIT_SAMPLES = 4000


def pack_mechanism(mech: HingeMechanism) -> np.ndarray:
    """Pack a `HingeMechanism` into the float64 array the kernels read, shape (30,).

    The layout is that of `archquake.mechanism.kinematics`. Link masses and inertias are
    sums over the links' voussoirs (parallel-axis theorem); G0, H0 are the gravity and ground
    terms of the equation of motion at phi = 0; the critical and toggle rotations come from
    `linkage_limits`.
    """
    arch = mech.arch
    a, b, c, d = mech.points
    out = np.zeros(PACKED_SIZE)
    out[AX:AY + 1], out[B0X:B0Y + 1], out[C0X:C0Y + 1], out[DX:DY + 1] = a, b, c, d
    out[SIGMA] = float(mech.opening_sign)
    u0, dv0 = c - b, d - b
    out[BRANCH] = 1.0 if (dv0[0] * u0[1] - dv0[1] * u0[0]) >= 0.0 else -1.0
    out[LBC] = math.hypot(*(c - b))
    out[LCD] = math.hypot(*(c - d))
    pivots = (a, b, d)
    for k, (rng, pivot) in enumerate(zip(mech.link_voussoirs, pivots)):
        idx = np.fromiter(rng, dtype=int)
        m = arch.voussoir_masses[idx]
        r = arch.voussoir_centroids[idx]
        mass = float(m.sum())
        centroid = (m[:, None] * r).sum(axis=0) / mass
        inertia = float(arch.voussoir_inertias[idx].sum() + (m * ((r - centroid) ** 2).sum(axis=1)).sum())
        base = LINK0 + 4 * k
        out[base] = mass
        out[base + 1:base + 3] = centroid - pivot
        out[base + 3] = inertia
    out[MASS] = arch.mass
    out[LENGTH] = arch.radius
    _, _, _, gg, hh = eom_terms(out, 0.0)
    out[G0], out[H0] = gg, hh
    crit, toggle = linkage_limits_compiled(out, _LIMIT_SAMPLES)
    out[PHI_CRIT], out[PHI_TOGGLE] = crit, toggle
    return out


def _canonical(mech: HingeMechanism) -> tuple[HingeMechanism, int]:
    """The row mechanism (opened by a ground acceleration towards -x) and the side that gives
    ``mech``: +1 for itself, -1 for the mirror image of the row (symmetric arches only)."""
    if mech.load_direction < 0 and mech.arch.symmetric:
        return mech.mirrored(), -1
    return mech, 1


def _meff0(packed: np.ndarray) -> float:
    return float(eom_terms(packed, 0.0)[1])


@dataclass(frozen=True)
class ImpactTable:
    """The mechanisms a time history may move on, packed, with what an impact of each does.

    Row i is a mechanism Q_i (side +1 in the kernel) whose mirror image is side -1. An impact of
    row i closing at rate |phi'| (either side) continues on row ``next_row[i]``, on side
    ``side * flip[i]``, opening at ``rate_ratio[i] |phi'|`` (the post mechanism's own phi, so
    ``rate_ratio`` is not c_v unless the two rows are one: the kinetic energies
    ``1/2 m_eff_i(0) phi'^2`` keep the ratio ``restitution_ct[i]`` exactly).

    Attributes
    ----------
    mechanisms : tuple of HingeMechanism
        Q_0 (the limit-analysis mechanism), Q_1, ... in the order the law reaches them.
    packed : ndarray (m, 30)
        `pack_mechanism` of each.
    next_row : ndarray (m,) int64
        Row after an impact of each row (-1: the post-impact mechanism is beyond the
        `MAX_REACHABLE` rows tabulated; the history stops there, flagged).
    flip : ndarray (m,) int64
        +-1: the side after the impact is the side before times this.
    rate_ratio : ndarray (m,)
        The law's post-impact opening rate per unit closing rate, rad/s per rad/s (0: rest).
    restitution_ct : ndarray (m,)
        The law's kinetic-energy ratio across each row's impact.
    validity : tuple of str
        Each row's impact validity (the law's, ``assumed`` for Eq. 4, `BEYOND_SET`).
    """

    mechanisms: tuple[HingeMechanism, ...]
    packed: np.ndarray
    next_row: np.ndarray
    flip: np.ndarray
    rate_ratio: np.ndarray
    restitution_ct: np.ndarray
    validity: tuple[str, ...]

    @property
    def size(self) -> int:
        return len(self.mechanisms)

    @property
    def complete(self) -> bool:
        """True if every impact stays in the set (no row is `BEYOND_SET`)."""
        return bool(np.all(self.next_row >= 0))

    def meff0(self) -> np.ndarray:
        """m_eff(0) of each row, kg m^2: the kinetic energy at phi = 0 is 1/2 m_eff(0) phi'^2."""
        return np.array([_meff0(p) for p in self.packed])

    def ratios(self, restitution: float | None = None) -> np.ndarray:
        """The kernel's rate ratios: the law's, or for a prescribed c_v the ones that keep the
        law's post-impact mechanism and give it c_v^2 of the kinetic energy before the impact
        (``c_v sqrt(m_eff_i(0) / m_eff_next(0))``; c_v itself when the next mechanism is the
        same row, as for Eq. 4). Where the law stops the arch (no post-impact mechanism) a
        prescribed c_v continues on the mirror image (next row = the row, flip -1)."""
        if restitution is None:
            return self.rate_ratio.copy()
        meff = self.meff0()
        nxt = np.where(self.next_row >= 0, self.next_row, np.arange(self.size))
        out = np.where(nxt == np.arange(self.size), restitution,
                       restitution * np.sqrt(meff / meff[nxt]))
        return np.where(self.next_row >= 0, out, 0.0)

    def restitution_cts(self, restitution: float | None = None) -> np.ndarray:
        """Kinetic-energy ratio across each row's impact under `ratios`."""
        if restitution is not None:
            return np.where(self.next_row >= 0, float(restitution) ** 2, 0.0)
        return self.restitution_ct.copy()

    def described(self, law: str, restitution: float | None = None) -> np.ndarray:
        """(m,) bool: the law describes each row's impact
        (`describes`, per row)."""
        from archquake.mechanism.impact import DESCRIBED

        if law == "paper":
            return np.array([restitution is not None or v == "assumed" for v in self.validity])
        return np.array([v in DESCRIBED for v in self.validity])

    def kernel_arrays(self, restitution: float | None = None
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(packed, next_row, flip, rate ratio): what the compiled kernels take."""
        return (np.ascontiguousarray(self.packed),
                np.ascontiguousarray(self.next_row, dtype=np.int64),
                np.ascontiguousarray(self.flip, dtype=np.int64),
                np.ascontiguousarray(self.ratios(restitution)))

    def hinges_label(self, row: int, side: int) -> str:
        """The hinges of row ``row`` on side ``side`` as ``"0i 3e 5i 7e"`` (memoised: a
        mirrored mechanism is validated again on construction, which cost 0.2 ms per event of
        every history)."""
        key = (int(row), -1 if side < 0 else 1)
        label = self._labels.get(key)
        if label is None:
            m = self.mechanisms[key[0]]
            if key[1] < 0:
                m = m.mirrored()
            label = " ".join(f"{j}{f.value[0]}" for j, f in zip(m.joints, m.faces))
            self._labels[key] = label
        return label

    @cached_property
    def _labels(self) -> dict[tuple[int, int], str]:
        return {}


@lru_cache(maxsize=16)
def _chain_rows(first: HingeMechanism, cap: int):
    """The reachable set of the chain law from ``first`` (and its mirror): rows, next, flip,
    c_T, validity, the law's post rates (see `ImpactTable`)."""
    from archquake.mechanism.impact_chain import chain_impact

    rows = [first]
    keys = {(first.joints, first.faces): 0}
    nxt, flip, ct, validity, post_rate = [], [], [], [], []
    i = 0
    while i < len(rows):
        sol = chain_impact(rows[i])
        if sol.post is None:
            nxt.append(i)
            flip.append(-1)
            ct.append(0.0)
            post_rate.append(0.0)
            validity.append(sol.validity)
        else:
            q, side = _canonical(sol.post)
            key = (q.joints, q.faces)
            if key not in keys and len(rows) < cap:
                keys[key] = len(rows)
                rows.append(q)
            j = keys.get(key, -1)
            nxt.append(j)
            flip.append(side)
            ct.append(sol.restitution_ct if j >= 0 else 0.0)
            post_rate.append(sol.post_rate if j >= 0 else 0.0)
            validity.append(sol.validity if j >= 0 else BEYOND_SET)
        i += 1
    return tuple(rows), nxt, flip, ct, validity, post_rate


def impact_table(prepared: PreparedMechanism, cap: int = MAX_REACHABLE) -> ImpactTable:
    """The `ImpactTable` of a prepared mechanism under its impact law.

    ``"paper"`` and ``"mirror"``: one row (the first mechanism), its impact onto its own mirror
    image (``next = 0``, ``flip = -1``) at the law's c_v (`PreparedMechanism.restitution`).
    ``"chain"``: start from the first mechanism, apply `chain_impact`
    to every row found (the mirror image of a row is the same row on the other side, since the
    law commutes with the mirror), up to ``cap`` rows. The rate ratio is the one that gives the
    post mechanism (packed phi) the law's c_T of the kinetic energy:
    ``sqrt(c_T m_eff_i(0) / m_eff_j(0))``, which is the law's ``post_rate`` measured on the row's
    own phi (a test holds the two equal).
    """
    law = prepared.impact.law
    if law != "chain":
        cv = prepared.restitution
        one = np.array([0], dtype=np.int64)
        return ImpactTable((prepared.mechanism,), prepared.packed[None, :].copy(), one,
                           np.array([-1], dtype=np.int64), np.array([cv]),
                           np.array([cv * cv]), (prepared.impact.validity,))
    rows, nxt, flip, ct, validity, _rates = _chain_rows(prepared.mechanism, int(cap))
    packed = np.empty((len(rows), PACKED_SIZE))
    packed[0] = prepared.packed
    for k in range(1, len(rows)):
        packed[k] = pack_mechanism(rows[k])
    meff = np.array([_meff0(p) for p in packed])
    nxt_a = np.array(nxt, dtype=np.int64)
    ct_a = np.maximum(np.array(ct, dtype=float), 0.0)
    safe = np.where(nxt_a >= 0, nxt_a, np.arange(len(rows)))
    ratio = np.where(nxt_a >= 0, np.sqrt(ct_a * meff / meff[safe]), 0.0)
    return ImpactTable(rows, packed, nxt_a, np.array(flip, dtype=np.int64), ratio, ct_a,
                       tuple(validity))


#: Packed kernel tables kept per prepared mechanism (one per prescribed c_v, and the law's).
KERNEL_TABLES = 8


@dataclass(frozen=True)
class PreparedMechanism:
    """A mechanism packed for the kernels, with its impact solution (reusable across runs).

    Build it with `build` (from an arch, a mechanism or a prepared mechanism).

    Attributes
    ----------
    mechanism : HingeMechanism
        The first mechanism, opened by a ground acceleration towards -x.
    packed : ndarray, shape (30,)
        `pack_mechanism` of it (the kernels' input; read it through the properties).
    impact : ImpactSolution
        Eq. 4 solved for this mechanism closing.

    Examples
    --------
    >>> import math
    >>> p = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> round(p.collapse_acceleration_g, 4), round(p.critical_rotation, 3) < round(p.toggle_rotation, 3)
    (0.37, True)
    """

    mechanism: HingeMechanism
    packed: np.ndarray
    impact: ImpactSolution

    @property
    def collapse_acceleration_g(self) -> float:
        """lambda: the equivalent static collapse acceleration of the mechanism, in g.

        The onset threshold the kernels use, G0 / |H0| (the gravity and ground terms of Eq. 2 at
        phi = 0): equal, by virtual work, to ``LimitAnalysis.collapse_acceleration_g`` for the
        hinges of the equivalent static analysis.
        """
        return float(self.packed[G0] / abs(self.packed[H0]))

    @property
    def critical_rotation(self) -> float:
        """Crest of the potential, rad: beyond it gravity can no longer close the mechanism."""
        return float(self.packed[PHI_CRIT])

    @property
    def toggle_rotation(self) -> float:
        """Rotation at which the linkage toggles (B, C, D collinear), rad (pi if it never does)."""
        return float(self.packed[PHI_TOGGLE])

    @property
    def restitution(self) -> float:
        """The c_v the time histories use: the impact model's, or 0 (perfectly plastic) where
        the model's is negative (inadmissible; see `ImpactSolution`)."""
        return max(self.impact.restitution_cv, 0.0)

    def restitution_for(self, restitution: float | None = None) -> float:
        """The c_v a time history uses: ``restitution`` if prescribed (checked once, here:
        `check_restitution`, [0, 1]), else `restitution`
        (the impact law's own)."""
        cv = check_restitution(restitution)
        return self.restitution if cv is None else cv

    @cached_property
    def table(self) -> ImpactTable:
        """The mechanisms the time history may move on under the impact law, with the impact
        table (`impact_table`; computed once, on first use)."""
        return impact_table(self)

    @property
    def follows_law(self) -> bool:
        """True if the time history moves on the mechanism the law selects after every impact
        it can reach (the whole reachable set is tabulated)."""
        return self.table.complete

    def member(self, row: int) -> PreparedMechanism:
        """Row ``row`` of `table` as a prepared mechanism (its own impact under the law is
        not re-solved: ``impact`` is the first mechanism's)."""
        if row == 0:
            return self
        return PreparedMechanism(self.table.mechanisms[row], self.table.packed[row].copy(),
                                 self.impact)

    def describes_impact(self, restitution: float | None = None) -> bool:
        """True if the impact law (with ``restitution`` prescribed or not) describes this arch's
        impacts (`describes`)."""
        return self.impact.describes(prescribed=restitution is not None)

    def kernel_table(self, restitution: float | None = None) -> Table:
        """The impact table under the law, packed for the compiled kernels
        (`archquake.mechanism._kernels.Table`), for a prescribed c_v ``restitution`` (already
        checked: `check_restitution`) or the law's (None). The no-return criterion is off on
        every row (``v_toggle`` nan): a record's run sets it.

        Memoised for the last `KERNEL_TABLES` values of ``restitution`` (building it costs more
        than a short time history's own overhead); the kernels only read it."""
        tables = self._kernel_tables
        packed = tables.get(restitution)
        if packed is None:
            table = self.table
            mechs, nxt, flip, ratio = table.kernel_arrays(restitution)
            packed = Table(mechs, nxt, flip, ratio,
                           np.ascontiguousarray(~table.described(self.impact.law, restitution)),
                           float(np.max(table.restitution_cts(restitution))),
                           np.full(mechs.shape[0], np.nan))
            if len(tables) >= KERNEL_TABLES:
                tables.pop(next(iter(tables)))
            tables[restitution] = packed
        return packed

    @cached_property
    def _kernel_tables(self) -> dict[float | None, Table]:
        return {}

    @classmethod
    def build(cls, arch_or_mechanism: VoussoirChain | HingeMechanism | PreparedMechanism,
              impact: str | None = None, *, loads=None) -> PreparedMechanism:
        """Prepare an arch (its hinges: `hinges_of`), a given mechanism (mirrored if a load
        towards -x opens it, so that the first mechanism is always the one a ground acceleration
        towards -x opens), or take a prepared mechanism. ``impact`` is the impact law
        (`archquake.mechanism.impact.IMPACT_LAWS`); None: a prepared mechanism's own, or
        `DEFAULT_IMPACT_LAW`. A prepared mechanism under another law is re-solved for that law only
        (the packed mechanism is kept).

        ``loads`` (a `Loads`, with an arch): each link carries
        its voussoirs' fill columns and moving loads
        (`CarryingChain`: mass, combined centroid,
        parallel-axis inertia, in the equation of motion and the impacts alike), and the hinges
        are the loaded arch's (`archquake.limit.loaded.loaded_collapse`, a load towards
        +x)."""
        if impact is not None:
            check_impact_law(impact)
        if loads is not None and not loads.empty:
            if not isinstance(arch_or_mechanism, VoussoirChain):
                raise InvalidParameterError("loads go with an arch, not with a mechanism")
            from archquake.geometry.carrying import CarryingChain
            from archquake.limit.loaded import loaded_collapse, seismic_case

            chain = CarryingChain(arch_or_mechanism, loads)
            if arch_or_mechanism.symmetric and not chain.symmetric:
                raise InvalidParameterError(
                    "the four-link model needs loads symmetric about the crown (its impacts "
                    "hand the motion to the mirror-image mechanism): use the rigid chain or the "
                    "DEM")
            found = loaded_collapse(seismic_case(arch_or_mechanism, loads)).mechanism
            arch_or_mechanism = HingeMechanism(chain, found.joints, found.faces)
        if isinstance(arch_or_mechanism, PreparedMechanism):
            prep = arch_or_mechanism
            if impact is None or impact == prep.impact.law:
                return prep
            return replace(prep, impact=solve_impact(prep.mechanism, impact))
        impact = DEFAULT_IMPACT_LAW if impact is None else impact
        if isinstance(arch_or_mechanism, HingeMechanism):
            mech = arch_or_mechanism
            if mech.load_direction < 0:
                mech = mech.mirrored()
        elif isinstance(arch_or_mechanism, VoussoirChain):
            mech = hinges_of(arch_or_mechanism)
        else:
            raise InvalidParameterError(
                f"expected an Arch or a HingeMechanism, got {type(arch_or_mechanism).__name__}"
            )
        return cls(mech, pack_mechanism(mech), solve_impact(mech, impact))


def link_masses(mechanism: HingeMechanism) -> dict | None:
    """The masses of a four-link mechanism whose voussoirs carry loads (its arch a
    `archquake.geometry.carrying.CarryingChain`; None for a bare arch), for JSON: the
    masonry's and the carried, in all and per link AB, BC, CD, kg; the passive pressure is
    left out of the dynamics (`archquake.blocks.assembly.PASSIVE_LEFT_OUT`)."""
    from archquake.blocks.assembly import PASSIVE_LEFT_OUT
    from archquake.geometry.carrying import CarryingChain
    from archquake.geometry.loads import held_joints

    chain = mechanism.arch
    if not isinstance(chain, CarryingChain):
        return None
    carried = chain.voussoir_masses - chain.base.voussoir_masses
    held = held_joints(chain.base, chain.loads.backing)
    links = mechanism.link_voussoirs
    return {"masonry_mass_kg": float(chain.base.mass), "carried_mass_kg": float(carried.sum()),
            "link_masses_kg": [float(chain.voussoir_masses[list(r)].sum()) for r in links],
            "link_carried_masses_kg": [float(carried[list(r)].sum()) for r in links],
            "voussoir_masses_kg": [float(m) for m in chain.voussoir_masses],
            "carried_masses_kg": [float(m) for m in carried],
            "held_by_backing": [int(k) for k in np.flatnonzero(held[:-1] | held[1:])],
            "passive_pressure": PASSIVE_LEFT_OUT}


__all__ = ["BEYOND_SET", "DEFAULT_IMPACT_LAW", "MAX_REACHABLE", "ImpactTable", "PreparedMechanism",
           "impact_table", "link_masses", "pack_mechanism"]
