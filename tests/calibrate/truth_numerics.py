"""The numerics of every joint generator's truth: the wear loop converged, whatever the believed
model's blocks.

A real joint has no wear blocks. The generators run their truths with the wear loop, so its
numerical error would be hidden in the data as if it were physics: on the tests' coarse believed
model (f = 0.25, one wear step per block) runs started 0-3 deg apart reach 180-224 um after
20,000 cycles where the converged loop reaches 141 um (README, the joint diagnosis's
resolution). Measured by the wear-step bound f with two wear steps per block, the bore converges
at f = 0.0078 (140-143 um, runs 0.5 um apart); the truths take f = 0.0039 (141.1-141.6 um),
a level finer, so that the diagnosis's own resolution does not meet the truth's at one setting.
"""

from __future__ import annotations

import copy

TRUTH_WEAR_BLOCKS = {"max_depth_increment_fraction": 0.00390625, "wear_steps_per_block": 2}


def with_truth_numerics(config: dict) -> dict:
    """``config`` with the truths' converged wear blocks :data:`TRUTH_WEAR_BLOCKS`."""
    changed = copy.deepcopy(config)
    changed["wear_loop"].update(TRUTH_WEAR_BLOCKS)
    return changed
