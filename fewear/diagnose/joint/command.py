"""``fewear diagnose PROFILES.csv [MAX_WEAR.csv ...] --config MODEL.toml [--out DIR]`` on wear
measured on the joint: the believed model's misses, the cause, the extended config and its gain
(:mod:`fewear.diagnose.joint.diagnose`). Writes DIR/diagnosis.json, DIR/report.md,
DIR/joint_fits.png and DIR/extended.toml (the config lines that differ from the default), all or
nothing (:mod:`fewear.diagnose.joint.report`).
"""

from __future__ import annotations

import sys

from fewear.diagnose.core.report import print_verdict
from fewear.diagnose.joint.diagnose import diagnose_joint
from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.diagnose.joint.report import summarise, write_joint_outputs
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.io.config import load_config
from fewear.io.output import staged_output


def run(args) -> int:
    """The diagnosis of the joint data ``args.measured`` against the believed model of
    ``args.config`` (the embedded default without one), its outputs written to ``args.out``."""
    from mpi4py import MPI

    from fewear.loop.settings import run_sections

    comm = MPI.COMM_WORLD  # every rank diagnoses (sharing each forward run), rank 0 writes
    config = load_config(args.config, [*run_sections(), "joint_diagnose"])
    settings = JointDiagnoseSettings.from_config(config.pop("joint_diagnose"))
    data = read_joint_measurements(args.measured)
    if comm.rank == 0:
        print(f"fewear diagnose: {believed_model(args.config, config)}", file=sys.stderr,
              flush=True)
    diagnosis = diagnose_joint(data, config, settings)
    summary = summarise(diagnosis)
    with staged_output(args.out, comm) as stage:
        if comm.rank == 0:
            write_joint_outputs(diagnosis, summary, stage)
    if comm.rank == 0:
        print_verdict(summary, args.out, unit=" m", confounded=[
            f"also accepted (confounded): {group['cause']}" for group in summary["confounded"]])
    return 0


def believed_model(path, config: dict) -> str:
    """Which model the diagnosis takes as believed, its size, and (without ``--config``) that the
    embedded default is the full paper case, minutes per run."""
    from fewear.io.limits import mesh_size

    rod = config["wear_loop"]["rod_models"][0]
    cells = mesh_size(config)[1]
    size = (f"{rod} rod, a mesh of about {cells:,} quadrilaterals, "
            f"{config['wear_loop']['load_steps_per_cycle']} load steps per cycle")
    if path is not None:
        return f"believed model: {path} ({size}); forward runs follow, each reports its progress"
    return (f"no --config: the believed model is the embedded default config, the paper's case "
            f"({size}): each forward run of it takes minutes, and a diagnosis makes dozens; "
            "progress follows. For a quicker diagnosis give your model as --config "
            "(`fewear config` prints the default to start from; a coarser [mesh] and fewer "
            "[wear_loop] load_steps_per_cycle run much faster)")
