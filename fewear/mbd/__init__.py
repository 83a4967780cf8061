"""Planar multibody dynamics compiled with numba (the whole step loop; ``jit``: the decorator
and its cache): rigid bodies, ANCF beams, clearance joints.

- ``points``, ``constraints``, ``system``: bodies' material points, holonomic constraints
  (revolute, prismatic, fixed angle, driven angle at constant speed or from a periodic table)
  and the assembled system M q'' + Phi_q^T lambda = Q;
- ``integrator``: index-3 generalized-alpha with step-size control around impacts;
- ``contact``, ``clearance``: contact laws (Lankarani-Nikravesh, Hunt-Crossley, Flores,
  tabulated), regularised friction, the clearance profile c(theta), the clearance joint;
- ``ancf``: the planar shear-deformable ANCF beam;
- ``description``, ``mechanism``: any mechanism as data (bodies with named points, joints,
  drivers; parsed from a file by ``fewear.io.mechanism``, docs/mechanisms.md) and its system,
  assembly and simulation, one joint-load history per clearance joint;
- ``slider_crank``, ``history``, ``command``: the paper's mechanism from the config (a
  description), the joint-load history for the wear stage and the ``fewear dynamics`` command.

Entry points: ``fewear.mbd.mechanism.simulate`` on the typed inputs of
``fewear.io.mechanism.dynamics_inputs``;
``fewear.mbd.slider_crank.simulate_slider_crank`` for the paper's mechanism.
"""
