"""Make the SYNTHETIC stand-in pin-on-disc data set ``pin_on_disc_cuzn25al6fe3mn3_42crmo.csv``.

The seed paper fits its wear coefficient k(p, v) to pin-on-disc tests of a CuZn25Al6Fe3Mn3 pin
(235 HB) on a 42CrMo disc (60 HRC) but does not publish them. This script makes a stand-in in the
same form, in a plausible range; it is no measurement. Run it to regenerate the file bit for bit::

    python -m tests.data_makers.make_standin_pin_on_disc

The law (k in m^2/N, p in Pa, v in m/s), :func:`standin_wear_coefficient_m2_N`:

    k(p, v) = K0 (p/P0)^ALPHA [1 + BETA ln^2(v/V0)] [1 + GAMMA q/(q + Q0)],  q = MU_NOMINAL p v,

a mild pressure rise of the specific wear rate, a minimum at moderate speed (adhesion at low speed,
heating at high speed) and a saturating rise with the frictional power density q [W/m^2] (softening
of the brass). Over 0.5-20 MPa and 0.05-2 m/s it spans about 1.3e-13 to 4.7e-13 m^2/N, i.e. a
dimensionless Archard K = k H of about 3e-4 to 1.1e-3 for H = 235 HB = 2.3 GPa
(``../shared/REFERENCES.md``: K about 4e-4 to 6e-4).

Test matrix: every pressure in PRESSURES_Pa with every velocity in VELOCITIES_m_s, one test each,
in a shuffled order; a pin of diameter PIN_DIAMETER_m (load F = p A); cumulative readings at
READING_DISTANCES_m. Scatter (NumPy ``default_rng(SEED)``, draws in the order of the code):
each test's k times a lognormal factor exp(TEST_SCATTER N(0, 1)) (test-to-test scatter), each
reading's volume times exp(READING_SCATTER N(0, 1)) (weighing and density errors); the friction
coefficient is MU_NOMINAL exp(0.08 N(0, 1)) per test times exp(0.03 N(0, 1)) per reading. Plain
Archard wear otherwise: V = k F s, no running-in, no transient, no heating history.
"""

from __future__ import annotations

import numpy as np

from fewear.data import STANDIN_PIN_ON_DISC_CSV

SEED = 20130601
K0_m2_N = 1.6e-13
P0_Pa = 2.0e6
ALPHA = 0.15
V0_m_s = 0.3
BETA = 0.06
GAMMA = 0.8
Q0_W_m2 = 5.0e5
MU_NOMINAL = 0.12
PRESSURES_Pa = (0.5e6, 1.0e6, 2.0e6, 5.0e6, 10.0e6, 20.0e6)
VELOCITIES_m_s = (0.05, 0.1, 0.25, 0.5, 1.0, 2.0)
PIN_DIAMETER_m = 6.0e-3
READING_DISTANCES_m = (100.0, 200.0, 300.0, 400.0, 500.0)
TEST_SCATTER = 0.15
READING_SCATTER = 0.02
OUTPUT = STANDIN_PIN_ON_DISC_CSV
COLUMNS = ("test_id", "pressure_Pa", "velocity_m_s", "sliding_distance_m", "wear_volume_m3",
           "time_s", "normal_load_N", "friction_coefficient")


def standin_wear_coefficient_m2_N(pressure_Pa, velocity_m_s):
    """The stand-in's underlying law k(p, v) in m^2/N (module docstring)."""
    p = np.asarray(pressure_Pa, float)
    v = np.asarray(velocity_m_s, float)
    q = MU_NOMINAL * p * v
    return (K0_m2_N * (p / P0_Pa) ** ALPHA * (1.0 + BETA * np.log(v / V0_m_s) ** 2)
            * (1.0 + GAMMA * q / (q + Q0_W_m2)))


def standin_rows() -> list[tuple]:
    """The data set's rows (test_id, p, v, s, V, t, F, mu) in file order."""
    rng = np.random.default_rng(SEED)
    area_m2 = np.pi * PIN_DIAMETER_m**2 / 4.0
    matrix = [(p, v) for p in PRESSURES_Pa for v in VELOCITIES_m_s]
    order = rng.permutation(len(matrix))
    rows = []
    for number, index in enumerate(order, start=1):
        p, v = matrix[index]
        load_N = p * area_m2
        k = standin_wear_coefficient_m2_N(p, v) * np.exp(TEST_SCATTER * rng.standard_normal())
        mu_test = MU_NOMINAL * np.exp(0.08 * rng.standard_normal())
        for s in READING_DISTANCES_m:
            volume = k * load_N * s * np.exp(READING_SCATTER * rng.standard_normal())
            mu = mu_test * np.exp(0.03 * rng.standard_normal())
            rows.append((f"T{number:02d}", p, v, s, volume, s / v, load_N, mu))
    return rows


def header() -> str:
    return "\n".join("# " + line if line else "#" for line in [
        "SYNTHETIC pin-on-disc data: a STAND-IN, not a measurement.",
        "CuZn25Al6Fe3Mn3 pin (235 HB) on 42CrMo disc (60 HRC), the pair of Zhao, Zhang & Dai",
        "(2013), whose test data are unpublished. Made by",
        f"tests/data_makers/make_standin_pin_on_disc.py (numpy default_rng({SEED})); rerun it to",
        "regenerate this file bit for bit.",
        "Law: k(p, v) = K0 (p/P0)^ALPHA [1 + BETA ln^2(v/V0)] [1 + GAMMA q/(q + Q0)], q = MU p v,",
        f"K0 = {K0_m2_N:g} m^2/N, P0 = {P0_Pa:g} Pa, ALPHA = {ALPHA}, V0 = {V0_m_s} m/s,",
        f"BETA = {BETA}, GAMMA = {GAMMA}, Q0 = {Q0_W_m2:g} W/m^2, MU = {MU_NOMINAL}.",
        f"Plain Archard: V = k F s with F = p A (pin diameter {PIN_DIAMETER_m:g} m). Lognormal",
        f"scatter: {TEST_SCATTER} per test on k, {READING_SCATTER} per reading on V; friction "
        "coefficient MU x lognormal(0.08)",
        "per test x lognormal(0.03) per reading. Tests run in a shuffled order of the 6 x 6 (p, v)",
        "matrix.",
        "",
        "One row per reading, cumulative within a test; SI units (in the column names).",
    ]) + "\n"


def standin_csv_text() -> str:
    lines = [",".join(COLUMNS)]
    for test_id, *values in standin_rows():
        lines.append(",".join([test_id] + [f"{x:.6g}" for x in values]))
    return header() + "\n".join(lines) + "\n"


def main() -> None:
    OUTPUT.write_text(standin_csv_text())
    print(f"wrote {OUTPUT}")


if __name__ == "__main__":
    main()
