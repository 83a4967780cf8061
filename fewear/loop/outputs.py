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

An ensemble (``[wear_loop] members`` > 1, :mod:`fewear.loop.ensemble`): the files above hold
member 0 (the run from the configured start, as a single run writes it; the XDMF files are
member 0's only), the figures the members' mean with bands of one standard deviation and of the
range, and beside them:

- ``summary.json`` ``ensemble``: ``members``, ``start_offsets_deg`` and per case and joint
  (``cases.<case>.joints.<joint>``) ``max_wear_depth_m``, ``max_wear_angle_deg`` (circular) and
  ``worn_volume_m3``, each as ``mean``, ``sd`` (ddof = 1), ``min``, ``max``, and ``members``:
  each member's summary as ``cases`` gives member 0's;
- ``wear_profile_members.csv`` ``case, joint, member, cycles, angle_deg, wear_depth_m`` and
  ``max_wear_members.csv`` ``case, joint, member, cycles, max_wear_depth_m``: each member's
  rows as the single run's files;
- ``wear_profile_ensemble.csv`` ``case, joint, cycles, angle_deg, mean_wear_depth_m,
  sd_wear_depth_m, min_wear_depth_m, max_wear_depth_m`` and ``max_wear_ensemble.csv`` ``case,
  joint, cycles, mean_max_wear_depth_m, sd_..., min_..., max_max_wear_depth_m``: the statistics
  at the union of the members' block ends, each member linear between its own.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from fewear.io.output import write_file_whole, write_json
from fewear.loop.progress import CaseProgress

SUMMARY, PROFILES_CSV, MAX_WEAR_CSV = "summary.json", "wear_profile.csv", "max_wear.csv"
PROFILES_PNG, MAX_WEAR_PNG = "wear_profiles.png", "max_wear.png"
PROFILES_MEMBERS_CSV, MAX_WEAR_MEMBERS_CSV = "wear_profile_members.csv", "max_wear_members.csv"
PROFILES_ENSEMBLE_CSV, MAX_WEAR_ENSEMBLE_CSV = ("wear_profile_ensemble.csv",
                                                "max_wear_ensemble.csv")
RUN_FILES = (SUMMARY, PROFILES_CSV, MAX_WEAR_CSV, PROFILES_PNG, MAX_WEAR_PNG,
             PROFILES_MEMBERS_CSV, MAX_WEAR_MEMBERS_CSV, PROFILES_ENSEMBLE_CSV,
             MAX_WEAR_ENSEMBLE_CSV)
"""The files of a run with fixed names (besides ``<case>.xdmf`` and ``.h5``); the last four
an ensemble's only."""


def write_run_outputs(folder: Path, cases: dict, joints: dict, config: dict,
                      history_source: str, ensemble: dict | None = None) -> None:
    """The run's files from ``cases`` (case -> joint name -> :class:`CaseProgress`) of the
    joints' typed inputs ``joints`` (joint name -> :class:`fewear.loop.settings.RunInputs`);
    ``history_source``: where the joint histories came from, in words; ``ensemble``: case ->
    its members' (member 0 first, ``cases``' own) joint name -> progress, None for one member."""
    loop = next(iter(joints.values())).loop
    summary = {
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
    }
    if ensemble is not None:
        summary = {**{key: value for key, value in summary.items() if key != "config"},
                   "ensemble": ensemble_summary(ensemble, joints), "config": config}
        write_ensemble_csvs(folder, ensemble)
    write_json(folder / SUMMARY, summary)
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


def ensemble_summary(ensemble: dict, joints: dict) -> dict:
    """The ``ensemble`` table of ``summary.json`` (the module's docstring)."""
    from fewear.loop.ensemble import joint_summary
    from fewear.loop.plan import Member

    members = len(next(iter(ensemble.values())))
    return {
        "members": members,
        "start_offsets_deg": [Member("", index).start_offset_deg for index in range(members)],
        "start": "member m: the driver started m degrees further on ([mechanism] "
                 "initial_crank_angle_deg + m, or a mechanism file's drivers' angle_deg + m)",
        "cases": {case: {"joints": {joint: joint_summary([case_summary(run[joint], inputs)
                                                          for run in runs])
                                    for joint, inputs in joints.items()}}
                  for case, runs in ensemble.items()},
    }


def write_ensemble_csvs(folder: Path, ensemble: dict) -> None:
    """The members' and the statistics' CSV files of an ensemble (the module's docstring)."""
    from fewear.loop.ensemble import STATISTICS, max_depth_statistics, profile_statistics

    joints = list(next(iter(ensemble.values()))[0])
    with open(folder / PROFILES_MEMBERS_CSV, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "member", "cycles", "angle_deg", "wear_depth_m"])
        for case, runs in ensemble.items():
            for joint in joints:
                for member, run in enumerate(runs):
                    angle = np.degrees(run[joint].state.angle_rad)
                    for record in run[joint].records:
                        writer.writerows((case, joint, member, record.cycles, f"{a:.6f}",
                                          f"{h:.9e}") for a, h in zip(angle, record.depth_m))
    with open(folder / MAX_WEAR_MEMBERS_CSV, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "member", "cycles", "max_wear_depth_m"])
        for case, runs in ensemble.items():
            for joint in joints:
                for member, run in enumerate(runs):
                    writer.writerow((case, joint, member, 0, f"{0.0:.9e}"))
                    writer.writerows((case, joint, member, r.cycles, f"{r.depth_m.max():.9e}")
                                     for r in run[joint].records)
    with open(folder / PROFILES_ENSEMBLE_CSV, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "cycles", "angle_deg",
                         *(f"{name}_wear_depth_m" for name in STATISTICS)])
        for case, runs in ensemble.items():
            for joint in joints:
                angle_rad, cycles, depth = profile_statistics([run[joint] for run in runs])
                for row, cycle in enumerate(cycles):
                    writer.writerows(
                        (case, joint, int(cycle), f"{np.degrees(a):.6f}",
                         *(f"{depth[name][row, node]:.9e}" for name in STATISTICS))
                        for node, a in enumerate(angle_rad))
    with open(folder / MAX_WEAR_ENSEMBLE_CSV, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["case", "joint", "cycles",
                         *(f"{name}_max_wear_depth_m" for name in STATISTICS)])
        for case, runs in ensemble.items():
            for joint in joints:
                cycles, depth = max_depth_statistics([run[joint] for run in runs])
                writer.writerow((case, joint, 0, *(f"{0.0:.9e}" for _ in STATISTICS)))
                writer.writerows((case, joint, int(cycle),
                                  *(f"{depth[name][row]:.9e}" for name in STATISTICS))
                                 for row, cycle in enumerate(cycles))


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
    """The bushing through the run: the unworn mesh and, per block, the node displacement.

    meshio's writer fills an HDF5 file held in memory, and both files are then written whole
    (:func:`write_file_whole`): HDF5 writing straight onto a full disk printed a traceback per
    dataset and crashed the process at exit (signal 11), and its message named no file."""
    from xml.etree import ElementTree

    import h5py
    import meshio

    reference = case.snapshots[0]
    points = np.column_stack([reference, np.zeros(len(reference))])
    cells = np.searchsorted(case.node_ids, case.cells)
    radial = reference / np.linalg.norm(reference, axis=1)[:, None]
    h5_path = path.with_suffix(".h5")
    writer = meshio.xdmf.TimeSeriesWriter(path)  # its XML names the .h5 by h5_filename
    writer.h5_filename = h5_path.name
    writer.h5_file = h5py.File(h5_path.name, "w", driver="core", backing_store=False)
    try:
        writer.write_points_cells(points, [("quad9", cells)])
        cycles = [0] + [record.cycles for record in case.records]
        for cycle, xy in zip(cycles, case.snapshots):
            displacement = xy - reference
            writer.write_data(float(cycle), point_data={
                "mesh_displacement_m": np.column_stack([displacement, np.zeros(len(xy))]),
                "radial_displacement_m": np.einsum("ij,ij->i", displacement, radial)})
        writer.h5_file.flush()
        h5_image = writer.h5_file.id.get_file_image()
    finally:
        writer.h5_file.close()
    write_file_whole(h5_path, h5_image)
    write_file_whole(path, ElementTree.tostring(writer.xdmf_file))
