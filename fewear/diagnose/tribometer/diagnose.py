"""What plain Archard gets wrong on measured pin-on-disc data, which physical causes explain it,
and how much better the extended model predicts tests it has not seen: forward selection of the
causes of :mod:`fewear.diagnose.tribometer.catalogue` on ln V, stage by stage, each judged on
left-out tests. The method: docs/diagnosis-method-notes.md."""

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


def diagnose(readings: Readings, settings: DiagnoseSettings | None = None,
             progress=None) -> Diagnosis:
    """The diagnosis of ``readings`` (docs/diagnosis-method-notes.md); ``progress(text)`` hears
    of each cause tried."""
    settings = settings or DiagnoseSettings.default()
    if readings.n_tests < 3:
        raise FewearInputError(
            f"{readings.source}: {readings.n_tests} test(s) with a usable reading "
            f"{readings.why_left_out()}; the diagnosis holds whole tests out and needs at least 3")
    test_group, labels = readings.test_groups()
    if np.bincount(test_group).max() < 2:
        raise FewearInputError(
            f"{readings.source}: every test is its own material group ({len(labels)} groups of "
            "the material and factor_* columns): a held-out test's level cannot be learnt "
            "from the other tests; the diagnosis needs a group of at least 2 tests")
    form = data_form(readings, settings)
    stages = [select_causes(reading_stage(readings, settings), settings.candidates, settings,
                            progress)]
    if form == "histories":
        stages.append(select_causes(across_stage(readings, stages[0], settings),
                                    settings.candidates, settings, progress))
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
