"""What plain Archard gets wrong on measured pin-on-disc data, which physical causes explain it,
and how much better the extended model predicts tests it has not seen.

Model of reading i of test j (wear volume V [m^3] after sliding distance s [m], time t [s], under
normal load F [N] or contact pressure p [Pa], speed v [m/s], frictional power q = mu p v):

.. math::  \\ln V_{ij} = \\ln F_j + c_{g(j)} + \\ln s_{ij}
           + \\sum_{\\text{causes}} \\ln m(\\ldots; \\theta) + \\epsilon_{ij},

plain Archard (the seed's eq. 10 integrated over a test, k = e^c) with one wear coefficient per
*material group* g (tests that share their material and every other declared categorical factor)
and multiplicative scatter: independent scatter of each reading (weighing, profilometry: readings
that dip below the previous one are data) and test-to-test scatter of k. The causes of
:mod:`fewear.diagnose.tribometer.catalogue` add ln m: *shape* laws bend the wear curve along sliding
(ln S_eff / s), *level* laws change k with load, pressure or p v.

The data decide how the causes are tested:

- *histories* (every test read at least ``min_readings_along_test`` times): the shape causes are
  tested along the tests with each test's own level c_j (stage "along tests": the test-to-test
  scatter of k stays out of it); the level causes then across tests on those levels (stage
  "across tests", one row per test);
- *tables* (a design of experiments, one reading per test or a few): one stage over all readings
  with the material-group levels; tests that share their conditions and differ in sliding
  distance form the wear curve V(s) across tests, so the shape causes are testable too.

Selection (forward, one cause at a time, while each still earns its place): at every step each
untried cause is fitted jointly with those already chosen (its form with the smallest residual sum
of squares) and scored on **whole tests held out**: leave-one-test-out, the cause's parameters
fitted on the other tests, the held-out test predicted from its conditions (with its own level
where the level is per test, so a transient that is over early still shows in the held-out curve).
Per held-out test u the mean squared log error e_u is compared with the current model's. The cause
is accepted when its evidence is significant at p below ``significance`` / m (Bonferroni over the
m forms tried at that step, since the best form of each cause is picked: a family-wise
false-positive rate of at most ``significance``), its
held-out error is lower than the current model's, and its AICc on all rows is at least
``min_aicc_improvement`` lower (Hurvich & Tsai 1989; Burnham & Anderson, *Model Selection and
Multimodel Inference*, 2002). The evidence is the test that is valid for the stage's scatter:

- along tests (many readings per held-out test, their scatter possibly correlated along the test,
  e.g. wear scattered interval by interval): a one-sided paired t-test over the held-out tests of
  ln(e_current,u / e_cause,u) > 0 (:func:`paired_improvement_p`), which counts tests, not
  readings, so correlated scatter cannot make a cause look significant;
- one row per test (levels across tests, tables of one reading per test): the rows are
  independent, and the extra-sum-of-squares F-test of the nested fits (Seber & Wild 1989) uses
  them all.

Of the accepted causes one joins the model: along tests the one with the smallest held-out error;
where each test is one row the one with the smallest AICc (with independent rows AICc and
leave-one-out cross-validation agree asymptotically, Stone, J. R. Stat. Soc. B 39 (1977) 44-47,
and AICc varies less between small samples).

Causes accepted at the first step of a stage that the held-out errors do not tell apart from the
one chosen (paired p >= ``significance``) are reported as confounded, with the evidence for each.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fewear.diagnose.tribometer.catalogue import ShapeLaw
from fewear.diagnose.tribometer.fitting import StageResult, select_causes
from fewear.diagnose.tribometer.readings import Readings
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.diagnose.tribometer.stages import (
    across_stage,
    data_form,
    log_k_per_test,
    reading_stage,
)
from fewear.errors import FewearInputError
from fewear.wear.coefficient import ConstantWearCoefficient, RbfWearCoefficient, wear_section
from fewear.wear.extensions import NoExtension, extension_to_config


@dataclass(frozen=True)
class Diagnosis:
    """Everything :func:`diagnose` found: the stages (their fits and the causes tried), the
    causes named (by held-out gain) and the extended model's [wear] section
    (:func:`fewear.diagnose.tribometer.report.summarise` makes the JSON-ready summary)."""

    readings: Readings
    settings: DiagnoseSettings
    form: str
    stages: tuple[StageResult, ...]
    causes: tuple[str, ...]
    extended_section: dict[str, Any] = field(repr=False)

    @property
    def cause(self) -> str:
        return self.causes[0] if self.causes else "none"

    @property
    def reading_stage(self) -> StageResult:
        """The stage whose rows are the readings ("along tests" or "all readings")."""
        return self.stages[0]

    @property
    def shape_law(self) -> ShapeLaw | None:
        laws = [law for law in self.reading_stage.final.laws if isinstance(law, ShapeLaw)]
        return laws[0] if laws else None


def diagnose(readings: Readings, settings: DiagnoseSettings | None = None) -> Diagnosis:
    """The diagnosis of ``readings`` (module docstring for the method)."""
    settings = settings or DiagnoseSettings.default()
    if readings.n_tests < 3:
        raise FewearInputError(f"{readings.source}: {readings.n_tests} test(s) with wear; the "
                               "diagnosis holds whole tests out and needs at least 3")
    form = data_form(readings, settings)
    stages = [select_causes(reading_stage(readings, settings), settings.candidates, settings)]
    if form == "histories":
        stages.append(select_causes(across_stage(readings, stages[0], settings),
                                    settings.candidates, settings))
    gains = {name: gain for stage in stages for name, gain in stage.gains.items()}
    causes = tuple(sorted(gains, key=lambda name: -gains[name]))
    extended = extended_wear_section(readings, stages[0], settings)
    return Diagnosis(readings, settings, form, tuple(stages), causes, extended)


def extended_wear_section(readings: Readings, result: StageResult,
                          settings: DiagnoseSettings) -> dict[str, Any]:
    """The ``[wear]`` section of the extended model: the shape cause as the extension, and
    k(p, v) trained on the tests' k under it (the RBF network of seed eq. 9 over the tests of the
    largest material group when they cover ``min_conditions_for_network`` distinct (p, v), else
    their geometric mean): the network carries what the level causes found."""
    log_k = log_k_per_test(readings, result.stage, result.final)
    test_group, _ = readings.test_groups()
    main = test_group == np.bincount(test_group).argmax()
    shape = [law for law in result.final.laws if isinstance(law, ShapeLaw)]
    extension = shape[0].extension if shape else NoExtension()
    model = ConstantWearCoefficient(float(np.exp(np.mean(log_k[main]))))
    if readings.pressure_Pa is not None and readings.velocity_m_s is not None:
        p = readings.per_test(readings.pressure_Pa)[main]
        v = readings.per_test(readings.velocity_m_s)[main]
        if len(set(zip(p, v))) >= settings.min_conditions_for_network:
            model, _ = RbfWearCoefficient.fit(p, v, np.exp(log_k[main]),
                                              folds=min(5, int(main.sum())))
    return wear_section(model, **extension_to_config(extension))
