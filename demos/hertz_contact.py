# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Hertz contact of the pin in the bushing bore
#
# A rigid pin of radius $R_p$ presses with the joint force $F$ (N) on the bore (radius $R_b$) of a
# linear elastic bushing (Young's modulus $E_b$, Poisson ratio $\nu_b$, width $L$) whose outer
# surface is clamped. The FE model (:mod:`fewear.contact.solver`) is plane strain with thickness
# $L$, serendipity degree-2 displacements on a structured O-grid, penalty contact of the bore
# against the rigid circle and force control of the pin centre. Its nodal pressures are the
# penalty law $p = k\langle -g \rangle_+$ at the bore nodes (vertices and edge midpoints), which
# are the Gauss-Lobatto points of its contact integral: they are the pressures whose weighted sum
# balances $F$.
#
# At a small load the contact strip is narrow ($a \ll R_b$) and Hertz's line contact applies
# (Johnson, *Contact Mechanics*, 1985, ch. 4), with the rigid pin and the concave bore:
#
# $$ \frac{1}{E^*} = \frac{1-\nu_b^2}{E_b}, \qquad R = \frac{R_b R_p}{R_b - R_p}, \qquad
#    P = \frac{F}{L}\ \mathrm{(N/m)}, $$
#
# $$ a = \sqrt{\frac{4 P R}{\pi E^*}}, \qquad p_0 = \sqrt{\frac{P E^*}{\pi R}}, \qquad
#    p(s) = p_0 \sqrt{1 - s^2/a^2}, $$
#
# with $s$ the arc length along the bore from the load direction (m) and $p$ in Pa. In two
# dimensions the approach of the pin depends on the size of the bushing (log terms), so only
# pressures and widths are compared, not the approach.
#
# The script solves the paper's joint (Table 1: $R_b$ = 10 mm, $R_p$ = 9.5 mm, $R_o$ = 15 mm,
# $L$ = 18 mm, brass $E_b$ = 90 GPa, $\nu_b$ = 0.32) on a sequence of bore element sizes, compares
# the peak pressure and the contact half-width with Hertz, fits the convergence rate and plots the
# finest field against the analytic one. Outputs go to ``$FEWEAR_DEMO_OUT`` (default
# ``out/demos/hertz_contact``); under ``mpirun -n 2`` only rank 0 prints and writes.
# `FEWEAR_DEMO_COARSE=1` runs two coarse meshes instead (0.75 and 1.25 bore elements in the Hertz
# half-width, 6 across the wall): seconds, for the test of the demo under MPI; too coarse for its
# errors to mean anything.

# +
import csv
import math
import os
from pathlib import Path

import numpy as np
from mpi4py import MPI

import fewear
from fewear.contact.analytic import compare_with_hertz, hertz_reference, wrap_angle_rad
from fewear.contact.params import contact_problem_from_config

COMM = MPI.COMM_WORLD
OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/hertz_contact"))


def report(*items):
    if COMM.rank == 0:
        print(*items, flush=True)
# -

# ## Parameters
#
# The load is small: the Hertz half-width is 2% of the bore radius (a contact half-angle of
# 1.15 degrees) and 4% of the wall, while the finest mesh still puts several bore elements across
# the strip. The force pushes the pin in the $-y$ direction, onto a vertex of the O-grid (the number
# of elements around the bore is a multiple of 4). The meshes put 1.25, 2.25, 3.25 elements in the
# Hertz half-width: the edge of the contact falls at the same place within an element on each, so
# the error falls steadily rather than jumping when the edge crosses a node.

# +
FORCE_N = 300.0                 # joint force on the pin (N), along -y
ELEMENTS_PER_HALF_WIDTH = (1.25, 2.25, 3.25)   # bore elements in the Hertz half-width a (-)
RADIAL_ELEMENT_COUNT = 14       # elements across the wall (-)
if os.environ.get("FEWEAR_DEMO_COARSE") == "1":
    ELEMENTS_PER_HALF_WIDTH, RADIAL_ELEMENT_COUNT = (0.75, 1.25), 6
RADIAL_GRADING_RATIO = 12.0     # outermost over innermost radial element size (-)

problem = contact_problem_from_config(fewear.load_config())
hertz = hertz_reference(problem, FORCE_N)
report(f"Hertz: P = {hertz.line_load_N_per_m:.4g} N/m, R = {hertz.relative_radius_m * 1e3:.4g} mm,"
       f" E* = {hertz.contact_modulus_Pa / 1e9:.4g} GPa")
report(f"       a = {hertz.half_width_m * 1e6:.4g} um "
       f"({math.degrees(hertz.contact_half_angle_rad):.3g} deg of bore), "
       f"p0 = {hertz.peak_pressure_Pa / 1e6:.4g} MPa")
# -

# ## FE solutions on refined meshes
#
# Each mesh refines the bore spacing $h$; the radial grading keeps the first ring of elements about
# as deep as it is long. Measured: the largest nodal pressure (the peak, the load direction being a
# node) and the contact half-width, three ways:
#
# - the second-moment width $a_m = 2\sqrt{\int p s^2 ds / \int p ds}$, exact for the Hertz
#   ellipse, integrated with the solver's nodal (Simpson) quadrature: every node contributes and
#   the value does not jump as the discrete edge moves (the convergence measure);
# - the Hertz ellipse fitted by least squares to the loaded nodes ($p^2$ is a quadratic in $s$);
# - the ends of the $p > 0$ zone, interpolated on the gap: with a stiff penalty the zero crossing of
#   the gap stays next to the last loaded node, so this one is short by about half a node spacing.


# +
def bore_element_size_m(elements_per_half_width):
    """h = 2 pi R_b / N, N the multiple of 4 just above 2 pi R_b (a/h) / a (m)."""
    circumference = 2 * math.pi * hertz.bore_radius_m
    count = 4 * math.ceil(circumference * elements_per_half_width / hertz.half_width_m / 4)
    return circumference / count


def solve_on(element_size_m):
    return fewear.solve_contact((0.0, -FORCE_N), config={"mesh": {
        "bore_element_size_m": element_size_m, "radial_element_count": RADIAL_ELEMENT_COUNT,
        "radial_grading_ratio": RADIAL_GRADING_RATIO}})


rows, results = [], []
for per_half_width in ELEMENTS_PER_HALF_WIDTH:
    element_size = bore_element_size_m(per_half_width)
    result = solve_on(element_size)
    results.append(result)
    comparison = compare_with_hertz(result, hertz)
    rows.append({
        "bore_element_size_m": element_size,
        "bore_elements": result.angle_rad.size // 2,
        "peak_pressure_Pa": comparison.peak_pressure_Pa,
        "peak_pressure_rel_error": comparison.peak_pressure_rel_error,
        "moment_half_width_m": comparison.moment_half_width_m,
        "moment_half_width_rel_error": comparison.moment_half_width_rel_error,
        "fit_half_width_rel_error": comparison.fit_half_width_rel_error,
        "zone_half_width_rel_error": comparison.zone_half_width_rel_error,
        "pin_centre_x_m": result.pin_centre_m[0],
        "pin_centre_y_m": result.pin_centre_m[1],
        "force_balance_rel_error": result.force_balance_rel_error,
        "newton_iterations": result.newton_iterations,
    })
finest = result
# -

# ## Convergence table
#
# The rate is the slope of $\log|e|$ against $\log h$ (least squares over all meshes).

# +
sizes = np.array([row["bore_element_size_m"] for row in rows])
rates = {
    name: float(np.polyfit(np.log(sizes), np.log([abs(row[name]) for row in rows]), 1)[0])
    for name in ("peak_pressure_rel_error", "moment_half_width_rel_error")
}
report(f"{'h (um)':>8} {'elements':>8} {'p_max (MPa)':>11} {'err p':>8} {'a_m (um)':>9} "
       f"{'err a_m':>8} {'err fit':>8} {'err zone':>8} {'Newton':>6}")
for row in rows:
    report(f"{row['bore_element_size_m'] * 1e6:8.2f} {row['bore_elements']:8d} "
           f"{row['peak_pressure_Pa'] / 1e6:11.4f} {row['peak_pressure_rel_error']:8.2%} "
           f"{row['moment_half_width_m'] * 1e6:9.2f} {row['moment_half_width_rel_error']:8.2%} "
           f"{row['fit_half_width_rel_error']:8.2%} {row['zone_half_width_rel_error']:8.2%} "
           f"{row['newton_iterations']:6d}")
report(f"fitted rates (slope of log|error| on log h): peak pressure "
       f"{rates['peak_pressure_rel_error']:.2f}, second-moment half-width "
       f"{rates['moment_half_width_rel_error']:.2f}")

if COMM.rank == 0:
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "convergence.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    with open(OUT / "rates.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["quantity", "rate"])
        writer.writerows(rates.items())
# -

# ## FE and Hertz pressures together
#
# The nodal pressures of the finest mesh against $p(s)$, as a function of the arc length from the
# load direction.

# +
if COMM.rank == 0:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    load_angle = -0.5 * math.pi
    arc_mm = 1e3 * hertz.bore_radius_m * wrap_angle_rad(finest.angle_rad - load_angle)
    near = np.abs(arc_mm) < 2.5e3 * hertz.half_width_m
    s_fine = np.linspace(-2.5 * hertz.half_width_m, 2.5 * hertz.half_width_m, 801)
    figure, axes = plt.subplots(figsize=(6.4, 4.2))
    axes.plot(1e3 * s_fine, hertz.pressure_Pa(s_fine) / 1e6, "k-", label="Hertz")
    axes.plot(arc_mm[near], finest.pressure_Pa[near] / 1e6, "o", markersize=4,
              label=f"FE nodes, h = {rows[-1]['bore_element_size_m'] * 1e6:.0f} um")
    axes.set_xlabel("arc length from the load direction s (mm)")
    axes.set_ylabel("contact pressure p (MPa)")
    axes.set_title(f"pin in bushing bore, F = {FORCE_N:g} N")
    axes.grid(alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(OUT / "hertz_pressure.png", dpi=120)
    plt.close(figure)
    report(f"wrote {OUT / 'convergence.csv'}, {OUT / 'rates.csv'}, {OUT / 'hertz_pressure.png'}")
# -
