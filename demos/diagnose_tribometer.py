# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # What plain Archard gets wrong on a pin-on-disc campaign, and why
#
# The seed paper (Zhao, Zhang & Dai 2013) predicts joint wear with Archard's law
#
# $$ V = k(p, v)\, F\, s $$
#
# (wear volume $V$ in m$^3$, normal load $F$ in N, sliding distance $s$ in m, wear coefficient $k$
# in m$^2$/N from an RBF network over contact pressure $p$ [Pa] and sliding speed $v$ [m/s],
# eq. 9), trained on pin-on-disc tests. A wear simulation then extrapolates the law to far longer
# sliding than any test. If the real wear rate is not constant along a test, that extrapolation is
# wrong, and a user bringing measured data should see it, learn why and get a better law.
#
# This demo runs the whole story on a shipped data set,
# ``fewear/data/pin_on_disc_running_in_synthetic.csv``. It is **synthetic**: a forward model with a
# departure from Archard hidden in it (the file's header says which and how it was made; the
# diagnosis below does not read the header). The steps:
#
# 1. fit the baseline (plain Archard per test, k(p, v) by the RBF network) and hold out the last
#    third of every test's readings to see how it extrapolates;
# 2. look at the residual pattern against every measured variable;
# 3. try the catalogue of causes, each a physical extension with two parameters
#    (``running_in``: $k(s) = k_{ss}[1 + (r-1) e^{-s/s_0}]$; ``time_transient``: the same over
#    time; ``thermal``: $k = k_b (1 + \beta\,\theta)$ with $\theta$ the lagged frictional power
#    $\mu p v$), scored on the held-out readings with a parsimony criterion;
# 4. name the cause, write the extended law as a ``[wear]`` config section, and measure the gain.
#
# Outputs go to ``$FEWEAR_DEMO_OUT`` (default ``out/demos/diagnose_tribometer``).

# +
import os
from pathlib import Path

import fewear
from fewear.calibrate.diagnose import DiagnoseSettings, diagnose, readings_from_measured
from fewear.calibrate.measured import read_measured_wear
from fewear.calibrate.report import write_outputs
from fewear.io.config import load_config

DATA = Path(fewear.__file__).parent / "data" / "pin_on_disc_running_in_synthetic.csv"
OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/diagnose_tribometer"))
OUT.mkdir(parents=True, exist_ok=True)
# -

# ## The measured data
#
# One row per reading, cumulative within a test: test id, $p$, $v$, $s$, $V$, time, load,
# friction coefficient. The reader checks units, monotonic readings and missing variables.

data = read_measured_wear(DATA)
readings = readings_from_measured(data)
print(f"{readings.n_tests} tests, {readings.test_index.size} readings; measured: "
      + ", ".join(data.available))

# ## Baseline, residuals, candidates
#
# The default ``[diagnose]`` settings (``fewear/defaults/diagnose.toml``): residuals of the wear
# between consecutive readings in log (wear scatters interval by interval), the last 34 % of each
# test's readings held out, a candidate accepted when it cuts the held-out error of the cumulative
# wear by 15 % or more, by more than one standard error across tests, and improves the AICc.

settings = DiagnoseSettings.from_config(load_config(None, sections=["diagnose"])["diagnose"])
result = diagnose(readings, settings)
summary = result.summary
baseline = summary["baseline"]
print(f"baseline: {baseline['coefficient_reason']}")
print(f"baseline held-out error (RMS of ln V): {baseline['held_out_error']:.3f}")

# What the baseline gets wrong, in words (Spearman rank correlations of the residuals):

for sentence in summary["residual_structure"]["sentences"]:
    print(" -", sentence)

# The candidates, each fitted on the training readings and scored on the held-out ones:

for candidate in summary["candidates"]:
    print(f" - {candidate['name']:15s} held-out error {candidate['held_out_error']:.3f}, "
          f"gain {candidate['gain']:+.0%}, {candidate['verdict']}")
for entry in summary["untestable"]:
    print(f" - {entry['name']:15s} {entry['message']}")

# ## The named cause and the gain

print(f"cause: {summary['cause']} ({summary['cause_meaning']})")
print(f"fitted parameters: {result.extended_fit.extension.params()}")
print(f"held-out error: baseline {summary['held_out_error']['baseline']:.3f} -> extended "
      f"{summary['held_out_error']['extended']:.3f}, gain {summary['gain']:.0%}")
for group in summary["confounded"]:
    print(f"confounded: {group['causes']}: {group['reason']}")

# What the extension changes in a prediction: the wear after twice each test's own sliding
# distance. Plain Archard, fitted through the running-in readings, takes the high early wear rate
# for the steady one.

prediction = summary["prediction"]
print(f"{prediction['what']}: extended / baseline = "
      f"{prediction['median_extended_over_baseline']:.2f} (median), range "
      f"{prediction['range_extended_over_baseline'][0]:.2f} to "
      f"{prediction['range_extended_over_baseline'][1]:.2f}")

# ## Outputs
#
# ``diagnosis.json``, ``report.md`` with the figures (measurement against baseline and extended
# model, residuals, candidates) and ``extended_wear.toml``: the ``[wear]`` section the simulation
# reads (``fewear.wear.extensions.wear_extension_from_config``). The same as
# ``fewear diagnose fewear/data/pin_on_disc_running_in_synthetic.csv --out DIR``.

paths = write_outputs(result, OUT)
for name, path in paths.items():
    print(f"{name:10s} {path}")

# ![fits](fits.png)
#
# ![residuals](residuals.png)
