"""A wear block with several wear steps (fewear.loop.block.wear_block): the steps are the blocks
they replace, with the dynamics run once."""

from dataclasses import replace

import numpy as np
import pytest
from mpi4py import MPI

from fewear.diagnose.joint.forward import wear_step_ends
from fewear.io.config import load_config
from fewear.loop import mechanism_adapter as adapter
from fewear.loop.block import (
    JointRun,
    mechanism_dynamics,
    new_bushing,
    new_case,
    run_block,
    wear_block,
)
from fewear.loop.checkpoint import Checkpoint
from fewear.loop.settings import run_inputs_from_config, run_sections
from fewear.mbd.slider_crank import CLEARANCE_JOINT
from tests.loop.test_wear_loop import write_config


@pytest.fixture(scope="module")
def small_config(tmp_path_factory):
    """The small case of tests/loop/test_wear_loop.py: rigid rod, 40 load steps, A = 2000 per
    step."""
    config = load_config(write_config(tmp_path_factory.mktemp("block")), run_sections())
    config["wear_loop"]["total_cycles"] = 7000
    return config


@pytest.fixture(scope="module")
def small_inputs(small_config):
    return run_inputs_from_config(small_config)


def first_dynamics(config, inputs, state):
    """The rigid case's first block of dynamics on ``state``'s bore (its histories, summary,
    final mechanism, wall time)."""
    return mechanism_dynamics("rigid", adapter.dynamics_inputs(config, "rigid"),
                              {CLEARANCE_JOINT: inputs}, {CLEARANCE_JOINT: state}, None)


def block_on(dynamics, joint: JointRun) -> None:
    """One wear block of ``joint`` on the given ``dynamics`` (as :func:`first_dynamics`)."""
    (histories, _, mechanism), seconds = dynamics
    wear_block({CLEARANCE_JOINT: joint}, histories, mechanism, seconds)


def test_wear_steps_of_one_block_are_the_blocks_they_replace_on_its_history(small_config,
                                                                             small_inputs,
                                                                             tmp_path):
    """Three wear steps on one recorded history leave the bore (depth to the last bit), the
    cycles and the mesh where three blocks given that same history leave them; the steps count
    as one block with one record, which keeps the bore after each inner step (as the blocks'
    records have it, and through a checkpoint). The last step is cut at total_cycles (2000 +
    2000 + 2000, then 1000 in a block of its own)."""
    stepped = replace(small_inputs, loop=replace(small_inputs.loop, wear_steps_per_block=3))
    cases = {}
    for name, inputs in (("steps", stepped), ("blocks", small_inputs)):
        bushing = new_bushing(inputs, MPI.COMM_SELF)
        case = new_case(bushing)
        dynamics = first_dynamics(small_config, inputs, case.state)
        blocks = 3 if name == "blocks" else 1
        for _ in range(blocks):
            block_on(dynamics, JointRun("rigid rod", inputs, bushing, case))
        cases[name] = (case, bushing)
    (steps, stepped_bushing), (blocks, block_bushing) = cases["steps"], cases["blocks"]
    assert steps.state.cycles == blocks.state.cycles == 6000
    np.testing.assert_array_equal(steps.state.depth_m, blocks.state.depth_m)
    assert steps.state.depth_m.max() > 0.0
    np.testing.assert_array_equal(stepped_bushing.snapshot().xy_m, block_bushing.snapshot().xy_m)
    assert (steps.state.blocks, len(steps.records), steps.records[0].block_cycles) == (1, 1, 6000)
    assert (blocks.state.blocks, len(blocks.records)) == (3, 3)
    assert steps.counts.ale_moves == blocks.counts.ale_moves == 3
    # the block's record keeps the bore after its inner steps: the first two blocks' records
    inner = steps.records[0]
    np.testing.assert_array_equal(inner.inner_cycles, [r.cycles for r in blocks.records[:2]])
    np.testing.assert_array_equal(inner.inner_depth_m, [r.depth_m for r in blocks.records[:2]])
    # the diagnosis's forward history reads the bore after every wear step either way
    nodes = steps.state.depth_m.size
    for stepped_, blocked in zip(wear_step_ends(steps.records, nodes),
                                 wear_step_ends(blocks.records, nodes)):
        np.testing.assert_array_equal(stepped_, blocked)
    # and so does a checkpoint
    checkpoint = Checkpoint(tmp_path, {"case": "stepped"})
    checkpoint.save("rigid", {"rod_slider": steps})
    loaded, = checkpoint.load(["rigid"], ["rod_slider"])["rigid"]["rod_slider"].records
    np.testing.assert_array_equal(loaded.inner_cycles, inner.inner_cycles)
    np.testing.assert_array_equal(loaded.inner_depth_m, inner.inner_depth_m)
    run_block(small_config, JointRun("rigid rod", stepped, stepped_bushing, steps))
    assert (steps.state.cycles, steps.records[-1].block_cycles, steps.state.blocks) == (7000, 1000,
                                                                                        2)


def test_wear_steps_per_block_outside_1_to_64_is_an_input_error(tmp_path, capsys):
    from fewear.cli import main

    config = write_config(tmp_path)
    config.write_text(config.read_text().replace("wear_steps_per_block = 1",
                                                 "wear_steps_per_block = 0"))
    assert main(["run", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert "wear_steps_per_block = 0: expected 1 to 64" in error
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("penetration_m, says", [
    (8.6e-6, "may get past it"), (4.2e-3, "jammed it into its worn pocket")])
def test_a_collapsed_block_says_whether_the_pin_jammed(small_config, small_inputs, monkeypatch,
                                                       penetration_m, says):
    """The wear loop's error on a collapsed step size tells a pin pressed in elastically (the
    undamped rod's 8.6 um: settings may get past it) from one pushed deeper than the radial
    clearance, 0.5 mm (a rigid rod's 4.2 mm at 79 MN, seen after 399,753 cycles: a jam, which
    no setting mends)."""
    from fewear.errors import FewearInputError
    from fewear.mbd.integrator import StepSizeCollapse
    from fewear.wear.state import WearState

    def collapsing(*args, **kwargs):
        raise StepSizeCollapse("generalized-alpha: step size fell below min_step_s",
                               ((penetration_m, 7.9e7, 0.1),))

    monkeypatch.setattr(adapter, "simulate", collapsing)
    worn = replace(WearState.unworn(np.linspace(0.0, 6.0, 48)), blocks=76, cycles=399_753)
    with pytest.raises(FewearInputError, match=says) as caught:
        first_dynamics(small_config, small_inputs, worn)
    assert "block 77 at 399,753 cycles" in str(caught.value)
