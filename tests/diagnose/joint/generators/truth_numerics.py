"""The numerics of every joint generator's truth: the wear loop converged, whatever the believed
model's blocks.

A real joint has no wear blocks. The generators run their truths with the wear loop, so its
numerical error would be hidden in the data as if it were physics: on the tests' coarse believed
model (f = 0.25, one wear step per block) runs started 0-3 deg apart reach 180-224 um after
20,000 cycles where the converged loop reaches 141 um (README, the joint diagnosis's
resolution). The error follows the wear step (the bound f and A_max), not how often the dynamics
are renewed: at 4,300-16,100 cycles, against the mean of three runs at f = 0.00098 with one wear
step per block (254 blocks), single runs at f = 0.0039 with one step per block are 0.72 um
(rigid rod) and 1.25 um (flexible rod) off, at f = 0.00195 with eight steps per block 0.28 and
0.44 um, at f = 0.00098 with eight 0.29 um (rigid; runs started 1-2 deg apart part by 0.3-0.4 um
at any setting). The truths take f = 0.00098 with eight wear steps per block (A_max halved with
f), a level finer than the diagnosis's own resolution reaches on these data.
"""

from __future__ import annotations

import copy

TRUTH_WEAR_BLOCKS = {"max_depth_increment_fraction": 0.0009765625,
                     "max_extrapolation_factor": 195.3125, "wear_steps_per_block": 8}


def with_truth_numerics(config: dict) -> dict:
    """``config`` with the truths' converged wear steps :data:`TRUTH_WEAR_BLOCKS`."""
    changed = copy.deepcopy(config)
    changed["wear_loop"].update(TRUTH_WEAR_BLOCKS)
    return changed
