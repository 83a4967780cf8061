"""Wall time of the wear loop on a mechanism file (prints its figures; `make bench`): the
four-bar with two worn clearance joints (``four_bar_two_joints``), both cases, over
FEWEAR_BENCH_CYCLES cycles (default 400,000: the issue's goal, under 3 minutes on a 2-core
machine), beside the paper's default slider-crank run (the embedded config, 400,000 cycles; about
1 min 45 s before mechanism files) measured in the same run, per case, joint and stage.

With the run config's bushing and the paper's wear coefficients the four-bar's crank-coupler
bushing (a full turn of relative rotation per cycle) wears through near 100,000 cycles
(docs/mechanisms.md); the 400,000-cycle run is therefore made as well with that joint
lubricated, its own wear table a constant k = 2e-14 m^2/N (a tenth of the dry pair's k at its
loads): the file a user with such a crank joint writes. A run that stops because a bushing is
worn through ([wear_loop] max_wall_fraction) is reported with its wall time."""

import json
import os
import time

import pytest

from fewear.cli import main
from fewear.io.mechanism import EXAMPLES_DIR

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "400000"))
LUBRICATED_CRANK_JOINT = ('name = "crank_coupler"\ntype = "revolute"\npin_point = "coupler.A"\n'
                          'bushing_point = "crank.A"\nclearance = true\n'
                          '[joints.wear]\ncoefficient_model = "constant"\n'
                          "constant_k_m2_N = 2.0e-14\n")


def lubricated_four_bar(folder) -> str:
    """The two-joint four-bar's file with its crank-coupler joint lubricated (path)."""
    text = (EXAMPLES_DIR / "four_bar_two_joints.toml").read_text()
    dry = LUBRICATED_CRANK_JOINT[:LUBRICATED_CRANK_JOINT.index("[joints.wear]")]
    assert dry in text
    path = folder / "four_bar_lubricated_crank.toml"
    path.write_text(text.replace(dry, LUBRICATED_CRANK_JOINT))
    return str(path)


def runs(folder) -> dict[str, str]:
    """Label -> config text of the runs compared."""
    cycles = f"[wear_loop]\ntotal_cycles = {CYCLES}\n"
    return {
        "four-bar, two worn joints": f'[mechanism]\nfile = "four_bar_two_joints"\n{cycles}',
        "four-bar, two worn joints, lubricated crank joint":
            f'[mechanism]\nfile = "{lubricated_four_bar(folder)}"\n{cycles}',
        "paper's slider-crank (default config)": "",
    }


def timed_run(tmp_path, name: str, text: str) -> tuple[int, float]:
    """`fewear run` of the config ``text`` into ``tmp_path / name``: exit code, wall time (s)."""
    config = tmp_path / f"{name}.toml"
    config.write_text(text)
    start = time.perf_counter()
    code = main(["run", "--config", str(config), "--out", str(tmp_path / name)])
    return code, time.perf_counter() - start


def test_wall_time_of_the_four_bar_beside_the_papers_run(tmp_path, capfd):
    load, lines = os.getloadavg()[0], []
    for index, (label, text) in enumerate(runs(tmp_path).items()):
        code, wall = timed_run(tmp_path, f"run{index}", text)
        error = capfd.readouterr().err.strip().splitlines() or ["(no message)"]
        if code != 0:
            lines.append(f"  {label}: stopped after {wall:.1f} s wall: {error[-1]}")
            continue
        summary = json.loads((tmp_path / f"run{index}" / "summary.json").read_text())
        lines.append(f"  {label}: {wall:.1f} s wall ({wall / 60:.2f} min)")
        for case, joints in summary["cases"].items():
            for joint, figures in joints["joints"].items():
                stages = figures["stage_wall_time_s"]
                lines.append(
                    f"    {case:8s} {joint:15s} {figures['cycles']:7,d} cycles, "
                    f"{figures['blocks']:4d} blocks, {figures['wall_time_s']:6.1f} s: "
                    + ", ".join(f"{stage} {seconds:.1f} s" for stage, seconds in stages.items())
                    + f"; max depth {figures['max_wear_depth_m']:.3e} m")
    with capfd.disabled():
        print(f"\nfewear run, both cases, default settings otherwise (load average before: "
              f"{load:.1f}):\n" + "\n".join(lines))
