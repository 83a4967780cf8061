# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # What plain Archard gets wrong on pin-on-disc data, and why
#
# The seed paper (Zhao, Zhang & Dai 2013) predicts joint wear with Archard's law
#
# $$ V = k\, F\, s $$
#
# (wear volume $V$ in m$^3$, normal load $F$ in N, sliding distance $s$ in m, wear coefficient $k$
# in m$^2$/N, in the paper an RBF network over contact pressure and sliding speed, eq. 9), trained
# on pin-on-disc tests. A wear simulation then extrapolates the law to far longer sliding and to
# other loads. If the real wear is not proportional to $F s$, the extrapolation is wrong, and a user
# bringing measured data should see it, learn why and get a better law.
#
# `fewear diagnose` fits plain Archard (one $k$ per material group) and tries a catalogue of
# causes, each a physical law with one or two parameters: *shape* laws that bend the wear curve
# along sliding (``running_in``, exponential or power-law; ``time_transient``; lagged
# ``thermal``), and *level* laws that change $k$ from test to test (``load_exponent``,
# $V \propto F^a$; ``mild_to_severe``, a jump above a load or $p v$ threshold; steady ``thermal``,
# an Arrhenius rate rising with the frictional power). Causes join one at a time while each
# predicts held-out tests significantly better (module docstring of
# ``fewear.diagnose.tribometer.diagnose``).
#
# Two data sets:
#
# 1. ``fewear/data/pin_on_disc_running_in_synthetic.csv``: **synthetic** histories with a
#    running-in hidden in it (its header says how it was made; the diagnosis does not read it): a
#    check that the answer comes out;
# 2. ``fewear/data/pin_on_disc_singh2016_al_sic.csv``: a **real, published** table (K. K. Singh
#    et al., Adv. Mater. Sci. Eng. 2016, Article ID 3813412, doi:10.1155/2016/3813412, CC BY):
#    the mass loss of an aluminium alloy and of an Al/SiC composite, dry and lubricated, at
#    10-30 N and two sliding speeds, one test per row, in the form of most tribology papers.
#
# Outputs go to ``$FEWEAR_DEMO_OUT`` (default ``out/demos/diagnose_tribometer``), one folder per
# data set.

# +
import os
from pathlib import Path

import numpy as np

from fewear.data import RUNNING_IN_SYNTHETIC_CSV as SYNTHETIC
from fewear.data import SINGH2016_AL_SIC_CSV as REAL
from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.measured import read_measured_wear
from fewear.diagnose.tribometer.readings import readings_from_measured
from fewear.diagnose.tribometer.report import summarise, write_outputs

OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/diagnose_tribometer"))


def show(summary):
    """The verdict, the causes tried at each step and what the report leaves unexplained."""
    print(f"causes: {summary['causes'] or 'none'} ({summary['cause_meaning']})")
    print(f"held-out error (RMS of ln V, leave one test out): "
          f"{summary['held_out_error']['baseline']:.3f} -> "
          f"{summary['held_out_error']['extended']:.3f}, gain {summary['gain']:.0%}")
    for stage in summary["stages"]:
        for number, step in enumerate(stage["steps"], start=1):
            for entry in step:
                params = ", ".join(f"{k} = {v:.3g}" for k, v in entry["params"].items())
                print(f"  {stage['name']}, step {number}: {entry['cause']} ({entry['form']}: "
                      f"{params}) {entry['verdict']}")
    for group in summary["confounded"]:
        print(f"confounded: {group['causes']}: {group['reason']}")
    for sentence in summary["unexplained"]:
        print(f"unexplained: {sentence}")
# -

# ## 1. Synthetic histories with a hidden running-in
#
# Nine tests (3 pressures x 3 speeds), ten cumulative readings each, 3 % noise per reading.

synthetic = diagnose(readings_from_measured(read_measured_wear(SYNTHETIC)))
synthetic_summary = summarise(synthetic)
show(synthetic_summary)
print("fitted:", synthetic.shape_law.params() if synthetic.shape_law else None)
(OUT / "synthetic").mkdir(parents=True, exist_ok=True)
write_outputs(synthetic, synthetic_summary, OUT / "synthetic")

# The header of the file says R = 5, S0 = 150 m: the fitted running-in should be close, and
# the prediction after twice each test's distance lower than plain Archard's (which takes the
# high early wear rate for the steady one):

prediction = synthetic_summary["prediction"]
print(f"{prediction['what']}: extended / baseline = "
      f"{prediction['median_extended_over_baseline']:.2f} (median)")

# ## 2. A real, published table
#
# The reader converts the mass losses with the printed densities (the notes say so), reads the
# material and the lubrication as categorical factors (each combination gets its own $k$), and
# uses the normal load where no contact pressure is given. One reading per test: the sliding
# distance differs between tests only with the speed (both run 600 s), which the report points
# out: an effect of distance cannot be told from an effect of speed here.

real = diagnose(readings_from_measured(read_measured_wear(REAL)))
real_summary = summarise(real)
for note in real_summary["notes"]:
    print("note:", note)
show(real_summary)
(OUT / "singh2016").mkdir(parents=True, exist_ok=True)
write_outputs(real, real_summary, OUT / "singh2016")

# The wear coefficient of each material group under plain Archard (m$^2$/N, geometric mean over
# its tests):

k = np.array(list(real_summary["baseline"]["k_per_test_m2_N"].values()))
test_group, group_names = real.readings.test_groups()
for number, name in enumerate(group_names):
    print(f"{name:55s} k = {np.exp(np.mean(np.log(k[test_group == number]))):.3g} m^2/N")

# ### Next to the authors' reading
#
# Singh et al. conclude (abstract) that the composite has a lower coefficient of friction and lower
# wear rates than the matrix alloy, dry and lubricated, and that the wear rates of both increase
# with increasing load; in their Tables 5 and 6 every wear rate at 3.77 m/s is also above its
# counterpart at 3.14 m/s. The diagnosis agrees, and says what it means for Archard's law:
#
# - the four material groups (alloy or composite, dry or lubricated) need their own $k$: the
#   composite's is less than half the alloy's, lubrication lowers both (printed above);
# - within a group $k$ is not constant. At the first step three laws in which $k$ rises with the
#   load each predict held-out tests significantly better than plain Archard: heating (``thermal``,
#   steady form: $k$ rising with the frictional power $F v$), a power of the load
#   (``load_exponent`` with $a$ above 1: the wear grows faster than the load) and a threshold in
#   $F v$ (``mild_to_severe``, reported as confounded with the heating). Heating joins first;
#   given it, a load exponent below 1 still earns its place (at equal $F v$ the wear grows less
#   than the load). With 24 tests in four groups the split between the load and the speed effect
#   is not sharp: read the pair as "the wear grows faster than $F s$ with load and speed", the
#   authors' own conclusion;
# - running-in (a falling $k$) is rejected, and the report notes that the sliding distance cannot
#   be told from the speed here (both runs lasted 600 s).
#
# A simulation that extrapolated plain Archard from these tests to other loads or speeds would
# under-predict the wear at high load and speed; the extended model carries the two laws.
