"""Independent reference solutions for the planar four-bar crank-rocker (stand-alone: no fewear
imports), for comparison tests of fewear's general planar mechanisms.

- ``freudenstein.FourBar``: the mechanism (SI); ``grashof``, ``kinematics(params, time_s)`` (closed
  form) and ``inverse_dynamics(params, time_s)`` (ideal rigid joint forces and driving torque).
- ``exudyn_four_bar.four_bar_cycle(variant, cycles_settle, step_s, ...)``: the same mechanism in
  Exudyn, variants "rigid", "cable" (ANCF-cable coupler) and "clearance" (Lankarani-Nikravesh
  contact at the coupler-rocker joint); ``clearance_cycle_statistics`` per crank turn.

Joint forces everywhere: global frame, N, exerted by the joint's first body on its second body
(O2: ground on crank, A: crank on coupler, B: coupler on rocker, O4: ground on rocker).
"""
