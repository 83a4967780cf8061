"""An ensemble's statistics: the members of a case (runs whose starts differ,
:class:`fewear.loop.plan.Member`) reduced to their mean, sample standard deviation and range.

The clearance joint's orbit is chaotic, so one run is one sample of the wear; the members'
spread is the honest uncertainty of the prediction. The members' blocks end at different crank
cycles (each chooses its own extrapolation), so the depths are compared on the union of their
block ends, each member's depth linear in the cycles between its own block ends (zero at cycle
0), as its ``wear_profile.csv`` rows give it. The depth's angle is a direction: its statistics
are circular (:func:`angle_statistics`).
"""

from __future__ import annotations

import numpy as np

STATISTICS = ("mean", "sd", "min", "max")


def statistics(values) -> dict:
    """``mean``, ``sd`` (the sample standard deviation, ddof = 1), ``min`` and ``max`` over the
    members (axis 0 of ``values``), as arrays (floats for 1-D ``values``)."""
    values = np.asarray(values, dtype=float)
    found = {"mean": values.mean(axis=0), "sd": values.std(axis=0, ddof=1),
             "min": values.min(axis=0), "max": values.max(axis=0)}
    return {name: (float(value) if np.ndim(value) == 0 else value)
            for name, value in found.items()}


def angle_statistics(angles_deg) -> dict:
    """Circular statistics of angles (deg): ``mean`` the direction of the mean unit vector, in
    [0, 360); ``sd``, ``min`` and ``max`` those of the members' deviations from it, each wrapped
    into [-180, 180) (so ``min`` may lie below 0 and ``max`` above 360). The deepest point may
    jump between two pockets: a large ``sd`` says so."""
    radians = np.radians(np.asarray(angles_deg, dtype=float))
    mean = float(np.degrees(np.arctan2(np.sin(radians).mean(), np.cos(radians).mean())) % 360.0)
    deviation = (np.asarray(angles_deg, dtype=float) - mean + 180.0) % 360.0 - 180.0
    return {"mean": mean, "sd": float(deviation.std(ddof=1)),
            "min": mean + float(deviation.min()), "max": mean + float(deviation.max())}


def block_cycles(runs: list) -> np.ndarray:
    """The union of the members' block ends (crank cycles, increasing)."""
    return np.unique(np.concatenate([[record.cycles for record in run.records]
                                     for run in runs]))


def member_profiles(runs: list, cycles: np.ndarray) -> np.ndarray:
    """Each member's depth profile (m) at ``cycles``: (members, cycles, nodes), linear between
    its block ends, zero at cycle 0."""
    angle = runs[0].state.angle_rad
    if not all(np.array_equal(run.state.angle_rad, angle) for run in runs):
        raise ValueError("the members' bore nodes lie at different angles")
    found = np.empty((len(runs), cycles.size, angle.size))
    for member, run in enumerate(runs):
        ends = np.array([0] + [record.cycles for record in run.records], dtype=float)
        depth = np.vstack([np.zeros(angle.size)] + [record.depth_m for record in run.records])
        for node in range(angle.size):
            found[member, :, node] = np.interp(cycles, ends, depth[:, node])
    return found


def member_max_depths(runs: list, cycles: np.ndarray) -> np.ndarray:
    """Each member's maximum depth (m) at ``cycles``: (members, cycles), linear between its
    block ends' maxima (its ``max_wear.csv`` rows), zero at cycle 0."""
    return np.array([np.interp(cycles, [0] + [record.cycles for record in run.records],
                               [0.0] + [float(record.depth_m.max()) for record in run.records])
                     for run in runs])


def profile_statistics(runs: list) -> tuple[np.ndarray, np.ndarray, dict]:
    """(bore node angles in rad, the union of the block ends, :func:`statistics` of the members'
    depth profiles there: each (cycles, nodes), m)."""
    cycles = block_cycles(runs)
    return runs[0].state.angle_rad, cycles, statistics(member_profiles(runs, cycles))


def max_depth_statistics(runs: list) -> tuple[np.ndarray, dict]:
    """(the union of the block ends, :func:`statistics` of the members' maximum depths there,
    m)."""
    cycles = block_cycles(runs)
    return cycles, statistics(member_max_depths(runs, cycles))


def joint_summary(members: list[dict]) -> dict:
    """The ensemble part of ``summary.json`` for one joint of a case from its members'
    summaries (:func:`fewear.loop.outputs.case_summary`, member 0 first): the statistics of the
    maximum depth, its angle and the worn volume, and each member's summary."""
    return {
        "max_wear_depth_m": statistics([m["max_wear_depth_m"] for m in members]),
        "max_wear_angle_deg": angle_statistics([m["max_wear_angle_deg"] for m in members]),
        "worn_volume_m3": statistics([m["worn_volume_m3"] for m in members]),
        "members": members,
    }
