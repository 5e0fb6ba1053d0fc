"""The traffic capacity of an arch: the multiplier on a traffic load that makes the arch a
mechanism, at one position and along the span (the adequacy factor of bridge assessment).

The arch carries its dead loads (self-weight, fill columns, loads on the extrados, backing:
`archquake.geometry.loads`); the traffic load, spread through the fill if asked, is the
live load that the multiplier mu scales (`archquake.limit.loaded`). The collapse load is
mu times the traffic load. Rigid blocks, no tension, no sliding, no crushing, no passive fill
pressure, no arching or strength of the fill: the fill is dead weight only, so the capacity
is on the safe side of what a fill's passive resistance would add.

Along the span, the critical position is the one of least mu. An undispersed axle passes from
one block to the next where it crosses a joint's extrados end; the least multiplier stays
continuous there (checked at every joint end in the tests), and a dispersed load is
continuous by construction.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from archquake._validate import require_instance
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import ArchquakeError, InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import HingeMechanism
from archquake.geometry.loads import BlockExtras, Extrados, Loads, Traffic, block_extras, traffic_actions
from archquake.limit.kinematic import MAX_KINEMATIC_VOUSSOIRS
from archquake.limit.loaded import (
    LoadedCollapse,
    _lp,
    _passive_resistance,
    _powers,
    _unstable,
    collapse_forces,
    loaded_collapse,
    stands,
    traffic_case,
)
from archquake.limit.thrust import JointForces

#: Most positions one scan takes.
MAX_POSITIONS = 2000


@dataclass(frozen=True)
class TrafficCapacity:
    """The collapse of an arch under its loads and a traffic load at one position.

    Attributes
    ----------
    arch : VoussoirChain
    loads : Loads
        Dead loads (no traffic).
    traffic : Traffic
    multiplier : float
        mu: the traffic load times mu collapses the arch (the adequacy factor at this
        position).
    mechanism : HingeMechanism
    joint_forces : JointForces
        At collapse, N and N m; ``thrust_points`` is the line of thrust.
    static_multiplier, kinematic_multiplier : float or None
        The two bounds (None where not computed).
    carried : BlockExtras
    extent_m : tuple of float
        x of the loaded length on the extrados, m.
    """

    arch: VoussoirChain
    loads: Loads
    traffic: Traffic
    multiplier: float
    mechanism: HingeMechanism
    joint_forces: JointForces
    static_multiplier: float | None
    kinematic_multiplier: float | None
    carried: BlockExtras
    extent_m: tuple[float, float]
    hinge_count: int = 4

    @property
    def collapse_load_N_m(self) -> float:
        """mu times the traffic load, N per metre of barrel width."""
        return self.multiplier * self.traffic.load

    @property
    def thrust_line(self) -> np.ndarray:
        return self.joint_forces.thrust_points

    def to_dict(self) -> dict:
        jf = self.joint_forces
        return {
            "arch": self.arch.describe(),
            "loads": self.loads.to_dict(),
            "traffic": self.traffic.to_dict(),
            "multiplier": self.multiplier,
            "collapse_load_kN_m": self.collapse_load_N_m / 1e3,
            "collapse_load_kN": self.collapse_load_N_m * self.arch.depth / 1e3,
            "static_multiplier": self.static_multiplier,
            "kinematic_multiplier": self.kinematic_multiplier,
            "hinges": [h.to_dict() for h in self.mechanism.hinges],
            "collapse_hinge_count": self.hinge_count,
            "loaded_extent_x_m": list(self.extent_m),
            "carried": self.carried.to_dict(),
            "joints": {"thrust_x": jf.thrust_points[:, 0], "thrust_y": jf.thrust_points[:, 1],
                       "normal_N": jf.normal, "eccentricity_m": jf.eccentricity},
        }


def _method(arch: VoussoirChain, method: str) -> str:
    if method == "auto":
        return "both" if arch.voussoirs <= MAX_KINEMATIC_VOUSSOIRS else "static"
    if method not in ("static", "kinematic", "both"):
        raise InvalidParameterError(f"method must be auto, static, kinematic or both, got "
                                    f"{method!r}")
    if method != "static" and arch.voussoirs > MAX_KINEMATIC_VOUSSOIRS:
        raise InvalidParameterError(
            f"the kinematic method needs voussoirs <= {MAX_KINEMATIC_VOUSSOIRS}, got "
            f"{arch.voussoirs}; use the static method")
    return method


def traffic_capacity(arch: VoussoirChain, loads: Loads, traffic: Traffic | None = None, *,
                     method: str = "auto", g: float = STANDARD_GRAVITY) -> TrafficCapacity:
    """The multiplier on ``traffic`` (default ``loads.traffic``) that collapses ``arch``
    carrying ``loads``.

    Examples
    --------
    >>> import math
    >>> from archquake.geometry.arch import Arch
    >>> from archquake.geometry.loads import Fill
    >>> arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
    >>> cap = traffic_capacity(arch, Loads(fill=Fill(depth=0.5)), Traffic(100e3, 2.5))
    >>> round(cap.multiplier, 3), cap.mechanism.joints
    (0.726, (2, 6, 11, 15))
    """
    require_instance("loads", loads, Loads, "a Loads")
    traffic = traffic or loads.traffic
    if traffic is None:
        raise InvalidParameterError("the traffic capacity needs a traffic load")
    require_instance("traffic", traffic, Traffic, "a Traffic")
    dead = loads.without_traffic()
    res = loaded_collapse(traffic_case(arch, dead, traffic, g=g), _method(arch, method))
    _, _, extent = traffic_actions(arch, dead, traffic)
    return _capacity(res, dead, traffic, block_extras(arch, dead, g=g), extent[0])


def _capacity(res: LoadedCollapse, dead: Loads, traffic: Traffic, carried: BlockExtras,
              extent: tuple[float, float]) -> TrafficCapacity:
    return TrafficCapacity(res.case.arch, dead, traffic, res.multiplier, res.mechanism,
                           res.joint_forces, res.static_multiplier, res.kinematic_multiplier,
                           carried, (float(extent[0]), float(extent[1])), res.hinge_count)


@dataclass(frozen=True)
class CapacityScan:
    """The traffic load's multiplier at every position along the span.

    Attributes
    ----------
    positions_m : ndarray, shape (p,)
        Along the clear span from the left intrados springing, m.
    multipliers : ndarray, shape (p,)
        inf where the load drives no mechanism (near a springing it only lifts the arch:
        no multiplier collapses it).
    hinges : ndarray of int, shape (p, 4)
        The collapse mechanism's joints at each position (-1 where there is none, or where
        the collapse needs more than four hinges).
    critical : TrafficCapacity
        At the position of least multiplier, with both bounds checked where the kinematic
        method applies.
    """

    positions_m: np.ndarray
    multipliers: np.ndarray
    hinges: np.ndarray
    critical: TrafficCapacity

    @cached_property
    def critical_index(self) -> int:
        return int(np.argmin(self.multipliers))

    @property
    def adequacy_factor(self) -> float:
        """The least multiplier along the span."""
        return self.critical.multiplier

    def to_dict(self) -> dict:
        return {"critical_position_m": self.critical.traffic.position,
                "adequacy_factor": self.adequacy_factor,
                "critical": self.critical.to_dict(),
                "scan": {"position_m": self.positions_m,
                         "multiplier": [float(m) if np.isfinite(m) else None
                                        for m in self.multipliers],
                         "hinge_joints": self.hinges}}


def capacity_scan(arch: VoussoirChain, loads: Loads, traffic: Traffic,
                  positions: np.ndarray | int = 50, *, method: str = "auto",
                  g: float = STANDARD_GRAVITY) -> CapacityScan:
    """The multiplier of ``traffic`` moved along the span.

    The dead loads and the mechanisms are built once; at each position the kinematic
    enumeration (up to `MAX_KINEMATIC_VOUSSOIRS` voussoirs)
    or the linear program gives mu. The critical position is then analysed again by
    `traffic_capacity` (both bounds where they apply).

    Parameters
    ----------
    arch : VoussoirChain
    loads : Loads
        The dead loads (a traffic in it is ignored).
    traffic : Traffic
        The load moved; its own position is ignored.
    positions : int or array_like
        Positions along the clear span, m, or how many evenly spaced ones from one springing
        to the other.
    method : {"auto", "static", "kinematic", "both"}
    g : float
        Gravity, m/s^2.

    Returns
    -------
    CapacityScan
    """
    require_instance("loads", loads, Loads, "a Loads")
    require_instance("traffic", traffic, Traffic, "a Traffic")
    dead = loads.without_traffic()
    ex = Extrados.of(arch)
    if np.ndim(positions) == 0:
        count = int(positions)
        if not 2 <= count <= MAX_POSITIONS:
            raise InvalidParameterError(f"positions must be from 2 to {MAX_POSITIONS}, got "
                                        f"{count}")
        pos = np.linspace(0.0, ex.clear_span, count)
    else:
        pos = np.asarray(positions, dtype=float).ravel()
        if not 1 <= pos.size <= MAX_POSITIONS:
            raise InvalidParameterError(f"give 1 to {MAX_POSITIONS} positions, got {pos.size}")
    chosen = _method(arch, method)
    base = traffic_case(arch, dead, traffic.at(float(pos[0])), g=g)
    scan_method = "static" if base.passive_limit.size else chosen  # see loaded._passive_collapse
    if not stands(base):
        raise _unstable(base)
    mus = np.empty(pos.size)
    hinges = np.empty((pos.size, 4), dtype=np.int64)
    if scan_method != "static":
        from archquake.limit.kinematic import admissible_mechanisms

        mechs = admissible_mechanisms(arch)
        mechs = mechs.subset(~base.held[mechs.joints].any(axis=1))
        p_dead = (_powers(mechs, base.dead_force, base.dead_moment)
                  - _passive_resistance(mechs, base))
    for i, s in enumerate(pos):
        live_f, live_m, _ = traffic_actions(arch, dead, traffic.at(float(s)))
        case = replace(base, live_force=live_f, live_moment=live_m)
        if scan_method == "static":
            try:
                res = loaded_collapse(case, "static")
                mus[i], hinges[i] = res.multiplier, res.mechanism.joints
                if res.hinge_count > 4:
                    hinges[i] = -1
            except ArchquakeError as exc:
                if "no collapse mechanism" in str(exc):
                    mus[i], hinges[i] = np.inf, -1
                elif "hinges" in str(exc):  # more than four: the program's multiplier stands
                    mus[i], hinges[i] = float(_lp(case)[0].x[3]), -1
                else:
                    raise
            continue
        p_live = _powers(mechs, live_f, live_m)
        ok = p_live > 1e-12 * float(np.max(np.abs(p_live), initial=0.0))
        if not np.any(ok):  # the load only lifts or holds every mechanism: it cannot collapse
            mus[i], hinges[i] = np.inf, -1
            continue
        cand = np.where(ok, -p_dead / np.where(ok, p_live, 1.0), np.inf)
        k = int(np.argmin(cand))
        mus[i], _ = collapse_forces(case, mechs.mechanism(k, arch))
        hinges[i] = mechs.joints[k]
    if not np.any(np.isfinite(mus)):
        raise ArchquakeError("no collapse mechanism: the traffic load cannot collapse the arch "
                             "at any position of the scan")
    crit = traffic_capacity(arch, dead, traffic.at(float(pos[int(np.argmin(mus))])),
                            method=chosen, g=g)
    return CapacityScan(pos, mus, hinges, crit)


__all__ = ["MAX_POSITIONS", "CapacityScan", "TrafficCapacity", "capacity_scan",
           "traffic_capacity"]
