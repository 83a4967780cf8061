"""A case's clearance joints split among the ranks of its communicator.

A case on several ranks gives each joint (round robin) a sub-communicator of its own for the FE
work (contact, wear, mesh); every rank runs the case's dynamics, which need every joint's worn
clearance, from the same wear states, so the ranks stay in step: each wear step covers the
fewest cycles any joint chose (an all-reduce), each block's worn states are shared before the
next dynamics, an input error in one joint's wear is raised on every rank, and the first rank
gathers what the other joints added in the block (their
progress, the new mesh snapshots only) to checkpoint and report the whole case. A joint alone
on its ranks computes exactly what it computes in the serial run, so the results are the same,
bit for bit. With one rank, or one joint, nothing is split and nothing is sent.
"""

from __future__ import annotations

import copy

from fewear.errors import FewearInputError


class JointRanks:
    """The joints ``names`` (in file order) of a case on ``comm``: ``mine`` the joints of this
    rank's group, worn on the sub-communicator ``sub``."""

    def __init__(self, names: list[str], comm):
        self.comm = comm
        self.groups = max(1, min(comm.size, len(names)))
        color = comm.rank % self.groups
        self.mine = names[color::self.groups]
        self.sub = comm if self.groups == 1 else comm.Split(color, comm.rank)
        self._sent: dict[str, int] = {}  # snapshots of each joint sent to the first rank so far

    @property
    def split(self) -> bool:
        return self.groups > 1

    def close(self) -> None:
        if self.split:
            self.sub.Free()

    def agreed(self, value=None, error: Exception | None = None) -> list:
        """Every rank's ``value``, once no rank failed: a rank's ``error`` (an input error in its
        joints' wear) is raised on every rank, so that none waits for the others in vain."""
        if not self.split:
            if error is not None:
                raise error
            return [value]
        values = self.comm.allgather((value, None if error is None else str(error)))
        failures = [message for _, message in values if message]
        if failures:
            raise FewearInputError(failures[0])
        return [value for value, _ in values]

    def all_states(self, mine: dict) -> dict:
        """Every joint's wear state (joint name -> state) from this group's ``mine``."""
        if not self.split:
            return dict(mine)
        shared = {}
        for part in self.comm.allgather(mine if self.sub.rank == 0 else {}):
            shared.update(part)
        return shared

    def gathered(self, mine: dict, whole: dict) -> None:
        """Bring ``whole`` (joint name -> progress, the first rank's view of the case) up to date
        with every group's ``mine`` after a block: the first rank's joints are its own objects,
        the others' arrive with the mesh snapshots they have not sent yet."""
        if not self.split:
            whole.update(mine)
            return
        parts = {}
        if self.sub.rank == 0 and self.comm.rank != 0:
            for name, progress in mine.items():
                sent = self._sent.get(name, 0)
                part = copy.copy(progress)
                part.snapshots = progress.snapshots[sent:]
                parts[name] = (part, sent)
                self._sent[name] = len(progress.snapshots)
        gathered = self.comm.gather(parts, root=0)
        if self.comm.rank != 0:
            return
        whole.update(mine)
        for part in gathered:
            for name, (progress, sent) in part.items():
                earlier = whole[name].snapshots[:sent] if name in whole else []
                progress.snapshots = earlier + progress.snapshots
                whole[name] = progress
