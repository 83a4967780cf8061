"""A checkpoint altered or damaged since it was written (issue 57): its cycles x100, a value
edited in its config, a mesh snapshot changed, or a NaN saved with a matching digest, is refused
on load naming the checkpoint and what to do; a genuine one reads back as it was saved. Built
from a small case progress, no FE run."""

import json

import numpy as np
import pytest

from fewear.loop.checkpoint import Checkpoint, CheckpointDamaged, payload_sha256
from fewear.loop.progress import BlockRecord, CaseProgress
from fewear.mbd.mechanism import MechanismState
from fewear.wear.extensions import SlidingState
from fewear.wear.state import WearState

CONFIG = {"wear_loop": {"total_cycles": 4000}}
NODES = 9


def progress() -> CaseProgress:
    """A joint after two blocks of 2,000 cycles: wear, records and three mesh snapshots."""
    angle = np.linspace(0.0, 2 * np.pi, NODES, endpoint=False)
    depth = np.linspace(1e-6, 2e-6, NODES)
    state = WearState(angle, depth, SlidingState(depth * 1e3, depth, 0 * depth, 4000.0), 4000, 2)
    records = [BlockRecord(cycles, 2000, depth * cycles / 4000, 10.0 * cycles, 0, 1e6, 1e-9,
                           np.array([cycles]), depth[None, :] * cycles / 4000)
               for cycles in (2000, 4000)]
    mesh = np.column_stack([np.cos(angle), np.sin(angle)]) * 0.01
    return CaseProgress(state=state, mechanism=MechanismState(0.3, np.arange(3.0), np.ones(3)),
                        records=records, snapshots=[mesh, mesh * 1.001, mesh * 1.002],
                        node_ids=np.arange(NODES), cells=np.arange(NODES)[None, :],
                        meshed_xy_m=mesh)


@pytest.fixture
def saved(tmp_path):
    store = Checkpoint(tmp_path, CONFIG)
    store.save("rigid", {"rod_slider": progress()})
    return store


def edit_case(store, edit, reseal=False):
    """Change the case file's arrays with ``edit`` (and recompute its digest when ``reseal``)."""
    path = store.case_path("rigid")
    with np.load(path, allow_pickle=False) as archive:
        arrays = {key: archive[key] for key in archive.files}
    edit(arrays)
    if reseal:
        arrays["sha256"] = np.array(payload_sha256(arrays))
    with open(path, "wb") as handle:
        np.savez(handle, **arrays)


def refusal(store) -> str:
    with pytest.raises(CheckpointDamaged) as error:
        store.load(["rigid"], ["rod_slider"])
    message = str(error.value)
    assert "altered or damaged" in message and "--overwrite" in message
    return message


def test_a_genuine_checkpoint_reads_back_as_saved(saved):
    loaded = saved.load(["rigid"], ["rod_slider"])["rigid"]["rod_slider"]
    original = progress()
    assert [record.cycles for record in loaded.records] == [2000, 4000]
    np.testing.assert_array_equal(loaded.state.depth_m, original.state.depth_m)
    np.testing.assert_array_equal(loaded.snapshots[2], original.snapshots[2])
    np.testing.assert_array_equal(loaded.mechanism.q, original.mechanism.q)


def test_cycles_edited_x100_are_refused(saved):
    def cycles_x100(arrays):
        arrays["rod_slider/record_cycles"] = arrays["rod_slider/record_cycles"] * 100

    edit_case(saved, cycles_x100)
    assert "rigid.npz" in refusal(saved)


def test_a_config_value_edited_in_the_metadata_is_refused(saved):
    def more_cycles(arrays):
        meta = json.loads(str(arrays["meta"]))
        meta["case"]["cycles"] *= 100
        arrays["meta"] = np.array(json.dumps(meta))

    edit_case(saved, more_cycles)
    refusal(saved)


def test_a_changed_mesh_snapshot_is_refused_by_name(saved):
    path = saved.mesh_path("rigid", "rod_slider", 1)
    np.save(path, np.load(path) * 2.0)
    assert "rigid-rod_slider-mesh-00001.npy" in refusal(saved)


@pytest.mark.parametrize("key", ["q", "rod_slider/meshed_xy_m", "rod_slider/record_values"])
def test_a_nan_with_a_matching_digest_is_refused_by_name(saved, key):
    """No run saves a NaN: refused even when the digest was made after it."""
    def nan(arrays):
        arrays[key] = arrays[key].astype(float)
        arrays[key].flat[0] = np.nan

    edit_case(saved, nan, reseal=True)
    message = refusal(saved)
    assert f"{key} holds non-finite values" in message and "min_step_s" not in message
