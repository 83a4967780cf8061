"""Planar multibody dynamics compiled with numba (the whole step loop; ``jit``: the decorator
and its cache): rigid bodies, ANCF beams, clearance joints.

- ``points``, ``constraints``, ``system``: bodies' material points, holonomic constraints
  (revolute, prismatic, driven angle) and the assembled system M q'' + Phi_q^T lambda = Q;
- ``integrator``: index-3 generalized-alpha with step-size control around impacts;
- ``contact``, ``clearance``: contact laws (Lankarani-Nikravesh, Hunt-Crossley, Flores,
  tabulated), regularised friction, the clearance profile c(theta), the clearance joint;
- ``ancf``: the planar shear-deformable ANCF beam;
- ``slider_crank``, ``history``, ``command``: the paper's mechanism from the config, the joint-load
  history for the wear stage and the ``fewear dynamics`` command.

Entry point: ``fewear.mbd.slider_crank.simulate_slider_crank``.
"""
