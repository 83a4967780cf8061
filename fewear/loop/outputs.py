"""The files ``fewear run`` writes (rank 0), read from the cases' results only.

- ``summary.json``: per case and clearance joint (``cases.<case>.joints.<joint>``) the maximum
  wear depth and its angle, the worn volume, cycles, blocks, ALE moves, re-meshes, wall time by
  stage; per case where its joint histories came from (``history_source``); the config used.
- ``wear_profile.csv``: long form ``case, joint, cycles, angle_deg, wear_depth_m`` after every
  block.
- ``max_wear.csv``: ``case, joint, cycles, max_wear_depth_m`` after every block (seed Fig. 7b).
- ``<case>-<joint>.xdmf`` (+ ``.h5``): a joint's bushing mesh with, per block (time = cycles),
  the mesh displacement from the unworn bushing and its radial part (at the bore: the wear
  depth), for ParaView (Warp By Vector with ``mesh_displacement_m`` shows the worn bushing).
- ``wear_profiles.png`` (seed Fig. 7a) and ``max_wear.png`` (seed Fig. 7b), drawn by the command
  (:func:`fewear.commands.run.write_run_figures`).
"""

from __future__ import annotations

import contextlib
import csv
from pathlib import Path

import numpy as np

from fewear.io.output import write_json
from fewear.loop.progress import CaseProgress

SUMMARY, PROFILES_CSV, MAX_WEAR_CSV = "summary.json", "wear_profile.csv", "max_wear.csv"
PROFILES_PNG, MAX_WEAR_PNG = "wear_profiles.png", "max_wear.png"
RUN_FILES = (SUMMARY, PROFILES_CSV, MAX_WEAR_CSV, PROFILES_PNG, MAX_WEAR_PNG)
"""The files of a run with fixed names (besides ``<case>.xdmf`` and ``.h5``)."""


def write_run_outputs(folder: Path, cases: dict, joints: dict, config: dict,
                      history_source: str) -> None:
    """The run's files from ``cases`` (case -> joint name -> :class:`CaseProgress`) of the
    joints' typed inputs ``joints`` (joint name -> :class:`fewear.loop.settings.RunInputs`);
    ``history_source``: where the joint histories came from, in words."""
    loop = next(iter(joints.values())).loop
    write_json(folder / SUMMARY, {
        "what": "seed section 5: wear at the clearance joints, block by block with the worn "
                "geometry fed back (ALE / re-meshing, worn clearance in the dynamics)",
        "load_steps_per_cycle": loop.load_steps_per_cycle,
        "recorded_cycles_per_block": loop.recorded_cycles_per_block,
        "extrapolation": loop.extrapolation.mode,
        "total_cycles": loop.total_cycles,
        "cases": {case: {"history_source": history_source,
                         "joints": {joint: case_summary(progress, joints[joint])
                                    for joint, progress in progress_of.items()}}
                  for case, progress_of in cases.items()},
        "config": config,
    })
    write_profiles_csv(folder / PROFILES_CSV, cases)
    write_max_wear_csv(folder / MAX_WEAR_CSV, cases)
    for case, progress_of in cases.items():
        for joint, progress in progress_of.items():
            write_xdmf(folder / xdmf_name(case, joint), progress)


def xdmf_name(case: str, joint: str) -> str:
    """The XDMF file of a case's joint (``fewear plot`` reads the two names back from it)."""
    return f"{case}-{joint}.xdmf"


def case_summary(case: CaseProgress, inputs) -> dict:
    """The numbers of one joint of a case for ``summary.json``."""
    state, geometry = case.state, inputs.contact.geometry
    peak = int(np.argmax(state.depth_m))
    first = case.records[0]
    return {
        "max_wear_depth_m": float(state.depth_m[peak]),
        "max_wear_angle_deg": float(np.degrees(state.angle_rad[peak])),
        "worn_volume_m3": geometry.width_m * state.worn_area_m2(geometry.inner_radius_m),
        "cycles": int(state.cycles),
        "blocks": int(state.blocks),
        "ale_moves": int(case.counts.ale_moves),
        "remeshes": int(case.counts.remeshes),
        "contact_cold_retries": int(case.counts.contact_retries),
        "contact_frictionless_steps": int(case.counts.frictionless_steps),
        "contact_dropped_steps": int(case.counts.dropped_steps),
        "first_block": {"cycles": first.block_cycles,
                        "max_wear_depth_per_cycle_m": first.max_depth_per_cycle_m,
                        "peak_contact_force_N": first.peak_contact_force_N,
                        "impacts": first.impacts,
                        "max_contact_pressure_Pa": first.max_contact_pressure_Pa},
        "last_block": {"cycles": case.records[-1].block_cycles,
                       "max_wear_depth_per_cycle_m": case.records[-1].max_depth_per_cycle_m,
                       "max_contact_pressure_Pa": case.records[-1].max_contact_pressure_Pa},
        "wall_time_s": case.wall_time_s,
        "stage_wall_time_s": dict(case.stage_wall_time_s),
    }


def write_profiles_csv(path: Path, cases: dict) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "cycles", "angle_deg", "wear_depth_m"])
        for case, progress_of in cases.items():
            for joint, progress in progress_of.items():
                angle = np.degrees(progress.state.angle_rad)
                for record in progress.records:
                    writer.writerows((case, joint, record.cycles, f"{a:.6f}", f"{h:.9e}")
                                     for a, h in zip(angle, record.depth_m))


def write_max_wear_csv(path: Path, cases: dict) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "cycles", "max_wear_depth_m"])
        for case, progress_of in cases.items():
            for joint, progress in progress_of.items():
                writer.writerow((case, joint, 0, f"{0.0:.9e}"))
                writer.writerows((case, joint, r.cycles, f"{r.depth_m.max():.9e}")
                                 for r in progress.records)


def write_xdmf(path: Path, case) -> None:
    """The bushing through the run: the unworn mesh and, per block, the node displacement."""
    import meshio

    reference = case.snapshots[0]
    points = np.column_stack([reference, np.zeros(len(reference))])
    cells = np.searchsorted(case.node_ids, case.cells)
    radial = reference / np.linalg.norm(reference, axis=1)[:, None]
    # meshio puts the .h5 beside the working directory, not beside the .xdmf: write from there
    with contextlib.chdir(path.parent), meshio.xdmf.TimeSeriesWriter(path.name) as writer:
        writer.write_points_cells(points, [("quad9", cells)])
        cycles = [0] + [record.cycles for record in case.records]
        for cycle, xy in zip(cycles, case.snapshots):
            displacement = xy - reference
            writer.write_data(float(cycle), point_data={
                "mesh_displacement_m": np.column_stack([displacement, np.zeros(len(xy))]),
                "radial_displacement_m": np.einsum("ij,ij->i", displacement, radial)})
