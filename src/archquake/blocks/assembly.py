"""Block assemblies for the block models (the distinct-element model and the rigid chain): an
arch on its abutments, a block on a base.

The arch's hinges come from the one place that answers "which hinges does this arch have",
`archquake.limit.hinges_of` (the equivalent static analysis), so the DEM
accepts every arch the four-link model accepts: any number of voussoirs, hinges anywhere.

An `Assembly` is the frozen description the solver packs into arrays: convex contact
polygons, exact mass properties, which blocks belong to the (prescribed) base, the joints
whose opening is recorded, the crown point and the rotation measure.

Contact stiffness. Joint stiffnesses k_n, k_s are given per unit area (Pa/m). Each
corner-to-edge contact is a spring of K = k * depth * L_trib (N/m), with the tributary length
L_trib fixed when the contact forms as half the shorter of the touched edge and the facing
edge of the touching block. Two faces in full contact (edge-to-edge, as at a closed arch
joint) are therefore represented, as in UDEC, by two corner contacts, one at each end, each
carrying half the joint length: together k_n * depth * t, the axial stiffness of the joint;
their rotational stiffness k_n * depth * t^3 / 4 is that of the two end springs (a continuous
joint would give t^3/12).
"""

from __future__ import annotations

import functools
import threading
from dataclasses import dataclass, field

import numpy as np

from archquake._validate import require_positive
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import HingeMechanism
from archquake.geometry.loads import Loads, block_extras
from archquake.geometry.polygon import polygon_mass_properties
from archquake.limit import hinges_of

#: What the DEM assembly of an arch is made of: every voussoir a block, or the arch cut only at
#: the four-link model's hinges (the paper's "three-voussoir arch", Figures 4(b), 6(a), 11).
VOUSSOIRS = "voussoirs"
HINGES = "hinges"
ASSEMBLIES = (VOUSSOIRS, HINGES)


@dataclass(frozen=True)
class Joint:
    """A joint between two blocks whose opening is recorded.

    ``points`` (2, 2): the joint's two end points in the undisplaced assembly, m (for an
    arch: intrados end, extrados end); ``faces``: their names. ``left``/``right``: block
    indices; the recorded opening at each end is the gap between the end point carried by
    ``right`` and the one carried by ``left``, along the joint normal (positive = open).
    """

    index: int
    left: int
    right: int
    points: np.ndarray
    faces: tuple[str, str] = ("intrados", "extrados")


@dataclass(frozen=True)
class RotationLink:
    """The rotation measure: rotation of the chord from point A (carried by block ``block_a``)
    to point B (carried by ``block_b``), times ``sign``, rad."""

    block_a: int
    point_a: np.ndarray
    block_b: int
    point_b: np.ndarray
    sign: int = 1


@dataclass(frozen=True)
class Assembly:
    """Rigid convex polygonal blocks, some of which form the moving base.

    Parameters
    ----------
    polygons : tuple of ndarray (k_i, 2)
        Convex contact polygons, counter-clockwise, undisplaced, m.
    masses, inertias : ndarray (nb,)
        kg and kg m^2 (about the centroid); ignored for base blocks.
    centroids : ndarray (nb, 2)
        m.
    base : ndarray (nb,) bool
        True for blocks moving with the ground (prescribed motion).
    depth : float
        Out-of-plane depth, m (turns stiffness per area into per length).
    joints : tuple of Joint
    reference_length : float
        Length for the relative thresholds (the arch thickness, the block width), m.
    base_level : float
        y below which a block's centroid means collapse, m.
    crown_block : int
        Block carrying the crown point (-1: none); ``crown_point`` its position, m.
    rotation_link : RotationLink
    outlines : tuple of ndarray, optional
        Drawing outlines (default: the polygons).
    """

    polygons: tuple
    masses: np.ndarray
    inertias: np.ndarray
    centroids: np.ndarray
    base: np.ndarray
    depth: float
    joints: tuple
    reference_length: float
    base_level: float
    crown_block: int
    crown_point: np.ndarray
    rotation_link: RotationLink
    outlines: tuple = ()
    name: str = "assembly"
    meta: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        nb = len(self.polygons)
        if nb < 2:
            raise InvalidParameterError(f"an assembly needs a base and at least one block, got {nb}")
        polys = tuple(np.array(p, dtype=float) for p in self.polygons)
        for i, p in enumerate(polys):
            if p.ndim != 2 or p.shape[1] != 2 or p.shape[0] < 3:
                raise InvalidParameterError(f"polygon {i} must have shape (k >= 3, 2), got {p.shape}")
            if _signed_area(p) <= 0:
                raise InvalidParameterError(f"polygon {i} must be counter-clockwise with area > 0")
        object.__setattr__(self, "polygons", polys)
        if not self.outlines:
            object.__setattr__(self, "outlines", polys)
        for name in ("masses", "inertias", "centroids", "base", "crown_point"):
            arr = np.array(getattr(self, name))
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        if not np.any(self.base) or np.all(self.base):
            raise InvalidParameterError("an assembly needs at least one base block and one free block")
        free = ~self.base
        if np.any(self.masses[free] <= 0) or np.any(self.inertias[free] <= 0):
            raise InvalidParameterError("every free block needs a mass > 0 kg and an inertia > 0 kg m^2")
        require_positive("depth", self.depth, "m")
        require_positive("reference_length", self.reference_length, "m")

    @property
    def n_blocks(self) -> int:
        return len(self.polygons)

    @property
    def radius(self) -> float | None:
        """The arch's radius, m, for an arch's assembly (default run windows scale with
        sqrt(R/g)); None for any other assembly."""
        arch = self.meta.get("arch")
        radius = arch.get("radius_m") if isinstance(arch, dict) else None
        return None if radius is None else float(radius)

    @property
    def free_blocks(self) -> np.ndarray:
        return np.flatnonzero(~self.base)

    @property
    def min_edge(self) -> float:
        """Shortest polygon edge, m."""
        return float(min(np.min(np.hypot(*(np.roll(p, -1, 0) - p).T)) for p in self.polygons))

    def to_dict(self) -> dict:
        return {
            "name": self.name,
            "blocks": int(np.sum(~self.base)),
            "base_blocks": int(np.sum(self.base)),
            "joints": len(self.joints),
            "reference_length_m": self.reference_length,
            **self.meta,
        }


def _signed_area(p: np.ndarray) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _sorted_ccw(points: np.ndarray) -> np.ndarray:
    c = points.mean(axis=0)
    ang = np.arctan2(points[:, 1] - c[1], points[:, 0] - c[0])
    return points[np.argsort(ang)]


#: How the dynamic models take passive fill pressure, stated in every result that carries a fill.
PASSIVE_LEFT_OUT = ("passive fill pressure not modelled in the dynamics: the fill adds mass "
                    "and weight, not resistance to the arch's sway")


@dataclass(frozen=True)
class LoadedVoussoirs:
    """Each voussoir with what it carries, for the block models (n voussoirs).

    Attributes
    ----------
    masses : ndarray, shape (n,)
        The voussoir's mass plus its fill column's and the loads that move with it, kg.
    centroids : ndarray, shape (n, 2)
        Their combined centroid, m.
    inertias : ndarray, shape (n,)
        Rotational inertia about the combined centroid (each part's own plus the
        parallel-axis term), kg m^2.
    held : ndarray of bool, shape (n,)
        Voussoirs the backing holds (a joint of theirs held: it cannot hinge, so nothing
        frees them from the support): part of the support.
    carried : ndarray, shape (n,)
        The carried mass alone, kg.
    mechanism : HingeMechanism
        The loaded arch's hinges (the equivalent static analysis with the loads, a load
        towards +x), which define the rotation measure.
    multiplier : float
        That analysis's collapse multiplier: the horizontal acceleration, in g, at which the
        loaded arch becomes a mechanism.
    """

    masses: np.ndarray
    centroids: np.ndarray
    inertias: np.ndarray
    held: np.ndarray
    carried: np.ndarray
    mechanism: HingeMechanism
    multiplier: float = float("nan")

    def to_dict(self) -> dict:
        return {
            "masonry_mass_kg": float(np.sum(self.masses - self.carried)),
            "carried_mass_kg": float(np.sum(self.carried)),
            "voussoir_masses_kg": [float(m) for m in self.masses],
            "carried_masses_kg": [float(m) for m in self.carried],
            "held_by_backing": [int(k) for k in np.flatnonzero(self.held)],
            "passive_pressure": PASSIVE_LEFT_OUT,
        }


def loaded_voussoirs(arch: VoussoirChain, loads: Loads) -> LoadedVoussoirs:
    """The voussoirs of ``arch`` with the loads they carry, as the block models take them.

    Each voussoir carries its fill column and the loads that move with the arch: their masses
    add to its own, at the combined centroid, with the rotational inertia about it by the
    parallel-axis theorem (a point load adds none of its own). The voussoirs the backing holds
    belong to the support. The hinges are the loaded arch's
    (`archquake.limit.loaded.loaded_collapse`).

    Loads whose mass does not move with the arch (a weight without inertia) need a force the
    block models do not apply, traffic is a statics load, and passive fill pressure is left
    out of the dynamics: the first two are refused, the last stated (`PASSIVE_LEFT_OUT`).

    Parameters
    ----------
    arch : VoussoirChain
    loads : Loads

    Returns
    -------
    LoadedVoussoirs
    """
    from archquake.limit.loaded import loaded_collapse, seismic_case

    if any(not p.moves_with_arch for p in loads.point_loads) or any(
            not d.moves_with_arch for d in loads.distributed_loads):
        raise InvalidParameterError(
            "loads marked 'still' (weight without mass) are statics only: the dynamic models "
            "carry loads whose mass moves with the arch")
    if loads.traffic is not None:
        raise InvalidParameterError("traffic is a statics load (see capacity), not carried in "
                                    "the dynamic models")
    if loads.passive is not None:
        raise InvalidParameterError(f"--passive: {PASSIVE_LEFT_OUT}; leave it out")
    ex = block_extras(arch, loads)
    vm, vc, vi = arch.voussoir_masses, arch.voussoir_centroids, arch.voussoir_inertias
    m = vm + ex.mass
    c = (vm[:, None] * vc + ex.mass[:, None] * ex.centroid) / m[:, None]
    inertia = (vi + vm * np.sum((vc - c) ** 2, axis=1)
               + ex.inertia + ex.mass * np.sum((ex.centroid - c) ** 2, axis=1))
    # a held joint cannot hinge, so the voussoir on its far side is bonded to the support too
    held = ex.held[:-1] | ex.held[1:]
    collapse = loaded_collapse(seismic_case(arch, loads, direction=1))
    return LoadedVoussoirs(m, c, inertia, held, ex.mass.copy(), collapse.mechanism,
                           float(collapse.multiplier))


def build_arch_assembly(
    arch: VoussoirChain,
    *,
    cut_joints: tuple[int, ...] | None = None,
    mechanism: HingeMechanism | None = None,
    hold_outside_hinges: bool = False,
    loads: Loads | None = None,
) -> Assembly:
    """The arch's voussoirs (or groups of them) on two abutments moving with the ground.

    Parameters
    ----------
    arch : Arch
    cut_joints : tuple of int, optional
        Build a coarser arch cut only at these joints (must include 0 and n), e.g. the
        paper's three-voussoir arch at the four-link hinges, ``(0, 3, 5, 7)`` for
        Oppenheim's arch (`three_voussoir_assembly`). Merged blocks get the exact merged
        mass properties of their voussoirs (Arch's annular-sector masses, centroids and
        inertias, combined with the parallel-axis theorem); their contact polygon is the convex
        hull of their joint end points (the intermediate intrados corners are dropped: contacts
        only occur at the cut joints, and the hull adds no mass).
    mechanism : HingeMechanism, optional
        The four-link mechanism whose first link defines the rotation measure; default the
        arch's hinges, `archquake.limit.hinges_of` (the equivalent static
        analysis, any number of voussoirs). Its hinges A and B must be cut joints.
    hold_outside_hinges : bool
        If True, the voussoirs outside the mechanism's outer hinges (between a springing and a
        hinge A or D that is not at it) belong to the support: they are base blocks moving with
        the ground, as the four-link model assumes (they stay on the ground). The mechanism's
        hinges A and D must then be cut joints.
    loads : Loads, optional
        What the arch carries (`loaded_voussoirs`): each voussoir's mass, centroid and
        inertia include its fill column and carried loads, the voussoirs the backing holds
        are base blocks, and the default mechanism is the loaded arch's. None or empty loads
        give the bare arch's assembly, unchanged.

    Notes
    -----
    Blocks 0 and 1 are the left and right abutments (base blocks). Each abutment is the
    trapezoid under its springing joint face down to one thickness below the lower springing
    point, with vertical sides through the joint's two ends, so that the springing joint face
    (inclined when the embrace is not 180 deg) is fully supported. Blocks 2.. are the
    voussoirs (groups) from left to right. Masses and inertias are Arch's exact
    annular-sector values, not the quadrilaterals' (the straight chords cut off a sliver).

    The rotation measure (``BlockResult.rotation``) is the rotation, in the opening sense of the
    first mechanism, of the chord from hinge A (carried by the block just right of joint A) to
    hinge B (carried by the block just left of joint B): for an arch cut at the hinges this is
    the rotation of link AB itself, the four-link phi; for the voussoir arch it is the
    rotation of voussoirs A..B as a whole, which equals phi while they move as one link.

    ``meta["collapse_multiplier"]`` is the equivalent static analysis's collapse multiplier
    of the arch with what it carries (g, a load towards +x; None where it finds none): the
    rigid chain starts its onset bisection from it (`archquake.rigid.verdict`).
    """
    n = arch.voussoirs
    cuts = tuple(range(n + 1)) if cut_joints is None else tuple(int(j) for j in cut_joints)
    if len(cuts) < 2 or cuts[0] != 0 or cuts[-1] != n or any(b <= a for a, b in zip(cuts, cuts[1:])):
        raise InvalidParameterError(
            f"cut_joints must be strictly increasing joint indices from 0 to {n}, got {cut_joints!r}"
        )
    loaded = None if loads is None or loads.empty else loaded_voussoirs(arch, loads)
    if mechanism is None:
        mechanism = hinges_of(arch) if loaded is None else loaded.mechanism
    ja, jb = mechanism.joints[0], mechanism.joints[1]
    if ja not in cuts or jb not in cuts:
        raise InvalidParameterError(
            f"hinges A, B at joints {ja}, {jb} must be cut joints {cuts} to measure the rotation"
        )
    held_below, held_above = (mechanism.joints[0], mechanism.joints[3]) if hold_outside_hinges else (0, n)
    if held_below not in cuts or held_above not in cuts:
        raise InvalidParameterError(
            f"hinges A, D at joints {held_below}, {held_above} must be cut joints {cuts} to hold "
            "the voussoirs outside them as part of the support"
        )
    ip, ep = arch.intrados_points, arch.extrados_points
    t = arch.thickness
    y_low = float(min(ip[0, 1], ep[0, 1]))
    y_bot = y_low - t
    polys, outlines, masses, inertias, cents, base = [], [], [], [], [], []
    for j in (0, n):
        pts = np.array([ip[j], ep[j], [ep[j, 0], y_bot], [ip[j, 0], y_bot]])
        poly = _sorted_ccw(pts)
        m, c, inertia = polygon_mass_properties(poly, arch.density, arch.depth)
        polys.append(poly)
        outlines.append(poly)
        masses.append(m)
        inertias.append(inertia)
        cents.append(c)
        base.append(True)
    vm, vc, vi = arch.voussoir_masses, arch.voussoir_centroids, arch.voussoir_inertias
    held = np.zeros(n, dtype=bool)
    if loaded is not None:
        vm, vc, vi, held = loaded.masses, loaded.centroids, loaded.inertias, loaded.held
    block_of_voussoir = np.zeros(n, dtype=int)
    for g, (j0, j1) in enumerate(zip(cuts, cuts[1:])):
        ks = np.arange(j0, j1)
        block_of_voussoir[ks] = g + 2
        m = float(vm[ks].sum())
        c = (vm[ks, None] * vc[ks]).sum(axis=0) / m
        inertia = float(np.sum(vi[ks] + vm[ks] * np.sum((vc[ks] - c) ** 2, axis=1)))
        poly = np.vstack([ip[j1], ep[j1 : j0 - 1 if j0 > 0 else None : -1], ip[j0]])
        polys.append(poly)
        outlines.append(_merged_outline(arch, j0, j1))
        masses.append(m)
        inertias.append(inertia)
        cents.append(c)
        base.append(j1 <= held_below or j0 >= held_above or bool(np.all(held[ks])))
    joints = []
    for idx, j in enumerate(cuts):
        left = 0 if j == 0 else block_of_voussoir[j - 1]
        right = 1 if j == n else block_of_voussoir[j]
        if loaded is not None and base[left] and base[right]:
            continue  # inside the backing: no joint to record (the event integrator's chain)
        joints.append(Joint(idx, int(left), int(right), np.array([ip[j], ep[j]])))
    crown_v = min(n // 2, n - 1)
    sign = mechanism.opening_sign
    link = RotationLink(
        int(block_of_voussoir[ja]),
        arch.joint_point(ja, mechanism.faces[0].value),
        int(block_of_voussoir[jb - 1]),
        arch.joint_point(jb, mechanism.faces[1].value),
        int(sign),
    )
    n_free = int(len(base) - np.count_nonzero(base))
    extra_meta = ({} if loaded is None or loads is None
                  else {"loads": loads.to_dict(), "masses": loaded.to_dict()})
    multiplier = _bare_multiplier(arch) if loaded is None else loaded.multiplier
    return Assembly(
        polygons=tuple(polys),
        masses=np.array(masses),
        inertias=np.array(inertias),
        centroids=np.array(cents),
        base=np.array(base),
        depth=arch.depth,
        joints=tuple(joints),
        reference_length=t,
        base_level=y_low,
        crown_block=int(block_of_voussoir[crown_v]),
        crown_point=np.asarray(arch.crown_point, dtype=float),
        rotation_link=link,
        outlines=tuple(outlines),
        name=f"arch ({n_free} blocks)",
        meta={
            "arch": arch.describe(),
            "cut_joints": list(cuts),
            "held_voussoirs": [int(k) for k in range(n)
                               if k < held_below or k >= held_above or held[k]],
            "mechanism_joints": list(mechanism.joints),
            "mechanism_faces": [f.value for f in mechanism.faces],
            "collapse_multiplier": multiplier,
            **extra_meta,
        },
    )


def _bare_multiplier(arch: VoussoirChain) -> float | None:
    """The bare arch's collapse multiplier (the equivalent static analysis of its hinges,
    `archquake.limit.hinges_of`), g; None where that analysis finds none."""
    from archquake.errors import ArchquakeError
    from archquake.limit.static import collapse_state

    try:
        return float(collapse_state(hinges_of(arch))[0])
    except (ArchquakeError, np.linalg.LinAlgError):
        return None


def three_voussoir_assembly(arch: VoussoirChain, *, loads: Loads | None = None) -> Assembly:
    """The arch cut only at its hinges (`archquake.limit.hinges_of`): the
    paper's three-voussoir arch (joints (0, 3, 5, 7) for Oppenheim's arch).

    The three moving blocks are the mechanism's links AB, BC and CD. Where a hinge A or D is
    not at its springing, the voussoirs between the springing and the hinge are one more block
    held as part of the support (moving with the ground), as in the four-link model.

    Examples
    --------
    >>> import math
    >>> a = three_voussoir_assembly(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> a.meta["cut_joints"], int((~a.base).sum())
    ([0, 3, 5, 7], 3)
    >>> b = three_voussoir_assembly(Arch(5.0, 0.6, math.pi, 15))
    >>> b.meta["cut_joints"], int((~b.base).sum()), b.meta["held_voussoirs"]
    ([0, 3, 7, 12, 15], 3, [0, 1, 2])
    """
    if loads is not None and not loads.empty:  # the loaded arch's hinges, its loaded blocks
        mech = loaded_voussoirs(arch, loads).mechanism
        cuts = tuple(sorted({0, *mech.joints, arch.voussoirs}))
        return build_arch_assembly(arch, cut_joints=cuts, mechanism=mech,
                                   hold_outside_hinges=True, loads=loads)
    mech = hinges_of(arch)
    cuts = tuple(sorted({0, *mech.joints, arch.voussoirs}))
    return build_arch_assembly(arch, cut_joints=cuts, mechanism=mech, hold_outside_hinges=True)


def dem_assembly(arch: VoussoirChain, assembly: str = VOUSSOIRS, *,
                 loads: Loads | None = None) -> Assembly:
    """The DEM assembly of ``arch`` carrying ``loads``: ``'voussoirs'`` (every voussoir a
    block, `build_arch_assembly`) or ``'hinges'`` (cut at the hinges,
    `three_voussoir_assembly`).

    Built once for equal inputs (the arch and the loads are frozen and compared by value),
    and one object for threads that ask at once: what is memoised on the assembly (the rigid
    chain's model, its onset accelerations found by bisection) is then computed once for
    every study of the same arch."""
    with _BUILDING:
        return _dem_assembly(arch, assembly, loads)


#: Held while an assembly is built, so that threads asking for the same one share it.
_BUILDING = threading.Lock()


@functools.lru_cache(maxsize=16)
def _dem_assembly(arch: VoussoirChain, assembly: str, loads: Loads | None) -> Assembly:
    if assembly == VOUSSOIRS:
        return build_arch_assembly(arch, loads=loads)
    if assembly == HINGES:
        return three_voussoir_assembly(arch, loads=loads)
    raise InvalidParameterError(f"assembly must be one of {ASSEMBLIES}, got {assembly!r}")


def _merged_outline(arch: VoussoirChain, j0: int, j1: int, per: int = 8) -> np.ndarray:
    if not isinstance(arch, Arch):  # any other shape: its block, or the chord polygon of a group
        if j1 == j0 + 1:
            return arch.block_polygons[j0].copy()
        ip, ep = arch.intrados_points, arch.extrados_points
        return np.vstack([ip[j0 : j1 + 1], ep[j1 : j0 - 1 if j0 > 0 else None : -1]])
    a0, a1 = arch.joint_angles[j0], arch.joint_angles[j1]
    ang = np.linspace(a1, a0, per * (j1 - j0))
    inner = arch.intrados_radius * np.column_stack([np.cos(ang), np.sin(ang)])
    outer = arch.extrados_radius * np.column_stack([np.cos(ang[::-1]), np.sin(ang[::-1])])
    return np.vstack([inner, outer])


def block_on_base(
    width: float,
    height: float,
    *,
    density: float = 2000.0,
    depth: float = 1.0,
) -> Assembly:
    """A rectangular block (``width`` b x ``height`` h, m) standing on a wide rigid base.

    Block 0 is the base (10 b wide, top face at y = 0), block 1 the block, centred on x = 0.
    The rotation measure is the block's counter-clockwise rotation; the crown point is the
    middle of its top face; the reference length is b; the single recorded joint is the
    block's bottom face (faces 'left', 'right' corners).

    Examples
    --------
    >>> asm = block_on_base(0.4, 2.0)
    >>> round(float(asm.masses[1]), 1), round(float(asm.inertias[1]), 2)  # m (b^2 + h^2) / 12
    (1600.0, 554.67)
    """
    b = require_positive("block width", width, "m")
    h = require_positive("block height", height, "m")
    base = np.array([[-5 * b, -b], [5 * b, -b], [5 * b, 0.0], [-5 * b, 0.0]])
    block = np.array([[-0.5 * b, 0.0], [0.5 * b, 0.0], [0.5 * b, h], [-0.5 * b, h]])
    m, c, inertia = polygon_mass_properties(block, density, depth)
    mb, cb, ib = polygon_mass_properties(base, density, depth)
    return Assembly(
        polygons=(base, block),
        masses=np.array([mb, m]),
        inertias=np.array([ib, inertia]),
        centroids=np.array([cb, c]),
        base=np.array([True, False]),
        depth=depth,
        joints=(Joint(0, 0, 1, np.array([[-0.5 * b, 0.0], [0.5 * b, 0.0]]), ("left", "right")),),
        reference_length=b,
        base_level=0.0,
        crown_block=1,
        crown_point=np.array([0.0, h]),
        rotation_link=RotationLink(1, np.array([-0.5 * b, 0.0]), 1, np.array([-0.5 * b, h]), 1),
        name=f"block {b:g} m x {h:g} m",
        meta={"width_m": b, "height_m": h, "density_kg_m3": density, "depth_m": depth},
    )


def loaded_body(arch, loads):
    """What a block model (the rigid chain, the DEM) runs for ``arch`` carrying ``loads``:
    the arch itself without loads (None or empty), else its assembly, every voussoir a block
    carrying its share (`build_arch_assembly`)."""
    if loads is None or loads.empty:
        return arch
    return build_arch_assembly(arch, loads=loads)


__all__ = [
    "ASSEMBLIES",
    "HINGES",
    "VOUSSOIRS",
    "Assembly",
    "Joint",
    "LoadedVoussoirs",
    "PASSIVE_LEFT_OUT",
    "RotationLink",
    "block_on_base",
    "build_arch_assembly",
    "dem_assembly",
    "loaded_body",
    "loaded_voussoirs",
    "three_voussoir_assembly",
]
