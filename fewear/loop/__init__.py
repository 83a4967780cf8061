"""The wear prediction of the seed paper (Zhao, Zhang & Dai 2013, Fig. 3), block by block.

The loop of ``fewear run`` follows the flowchart for each case (a connecting-rod model: rigid,
flexible), wearing every clearance joint of the mechanism together, each with its own FE bushing
and wear state (the paper's slider-crank has one, the rod-slider joint). Every wear block j:

1. **Dynamics** (:mod:`fewear.mbd`, through :mod:`~fewear.loop.mechanism_adapter`): the mechanism
   with every clearance joint on the worn clearance c(theta) = c0 + h(theta) of its wear state;
   the first block settles from the ideal mechanism, later ones start from the previous block's
   final state (a warm start: the orbit only adapts to the slightly larger clearances). Then
   ``recorded_cycles_per_block`` crank cycles are recorded: each joint's reaction and the pin's
   rotation relative to the bushing. A joint history imported from a file
   (``--joint-history``, :mod:`fewear.io.joint_history`) replaces this stage: the same history
   every block, no feedback of the wear to the dynamics.
2. **Load steps**: each recorded cycle cut into n steps (seed: 200); each step carries the joint
   force averaged over it and the relative rotation accumulated over it.
3. **Contact** (:mod:`fewear.contact`): the FE bushing on the worn bore (Q8, outer surface clamped,
   rigid pin on a pilot point) under each step's force: nodal pressures p and slips s.
4. **Wear** (:mod:`fewear.wear`): Archard's law with k(p, v) (seed eq. 9-10) and the wear law's
   history multiplier, per node, averaged over the recorded cycles; the wear step extrapolates it
   over A_j real cycles (fixed, or adaptive: bounded depth increment per step). Optionally impacts
   wear too, by the contact law's hysteresis work, the impacts' impulse or a power of their speed,
   each impact under its own footprint (the contact at its peak force) and the continuous
   contact's work under the steps' pressure (:mod:`fewear.wear.impact`, ``[wear] impact_*`` keys;
   default none).
5. **Geometry update**: the bore nodes move by the step's depth increment, the mesh follows (ALE)
   or is re-meshed from the worn bore, and the contact operator is rebuilt.

Stages 3-5 are one wear step; a block makes ``wear_steps_per_block`` of them on its recorded
cycles (the contact responds to the worn bore within tens of cycles, the dynamics far more
slowly), every joint's step over the same crank cycles (the fewest any joint's extrapolation
chose), then the next block runs its dynamics on the worn joints.

The worn bore has one source, :class:`fewear.wear.state.WearState`; the dynamics' clearance and the
mesh's bore are both derived from it. A checkpoint is written after every block
(:mod:`fewear.loop.checkpoint`): ``--resume`` continues an interrupted run to the same result.

The modules: :mod:`~fewear.loop.settings` (the typed inputs), :mod:`~fewear.loop.plan` (the
cases, joints and history source of a run), :mod:`~fewear.loop.stages` (stages
2-4 on one recorded history), :mod:`~fewear.loop.bushing` (the FE bushing on the worn bore),
:mod:`~fewear.loop.block` (one block, stages 1-5), :mod:`~fewear.loop.progress` (a case's run so
far), :mod:`~fewear.loop.checkpoint`, :mod:`~fewear.loop.outputs`, :mod:`~fewear.loop.ensemble`
(an ensemble's statistics: the members of a case, runs whose starts differ); the command is
:mod:`fewear.commands.run` (``fewear run``).
"""
