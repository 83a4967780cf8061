"""Independent reference solutions for the planar four-bar crank-rocker (stand-alone: no fewear
imports). ``freudenstein``: closed-form kinematics, Grashof check and rigid inverse dynamics;
``exudyn_four_bar``: the same mechanism simulated in Exudyn (rigid, ANCF-cable coupler,
clearance at the coupler-rocker joint)."""
