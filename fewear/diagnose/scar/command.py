"""``fewear diagnose SCAR.csv [--config FILE.toml] [--out DIR]`` on a measured wear scar: is the
believed scar model (``fewear scar``'s ``[scar] case`` with the source's wear coefficients)
wrong, by which cause, and its held-out gain (:mod:`fewear.diagnose.scar.diagnose`). Writes
DIR/diagnosis.json and DIR/profiles.png, all or nothing. The believed model runs here, the
causes' fits side by side in worker processes (one per core); ``[scar_diagnose]`` holds the
settings.
"""

from __future__ import annotations

import argparse
import sys

from fewear.diagnose.core.report import print_verdict
from fewear.diagnose.scar.diagnose import diagnose_scar
from fewear.diagnose.scar.measured import read_measured_scar
from fewear.diagnose.scar.report import summarise, write_outputs
from fewear.diagnose.scar.settings import ScarDiagnoseSettings
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.output import staged_output


def run(args: argparse.Namespace) -> int:
    """The diagnosis of the one scar file ``args.measured``, its outputs written to
    ``args.out``."""
    from fewear.diagnose.scar.forward import ScarModel
    from fewear.loop.scar import SCAR_SECTIONS

    if len(args.measured) != 1:
        raise FewearInputError(f"{len(args.measured)} files given: a measured scar is one file "
                               "(its repeated tests as columns)")
    config = load_config(args.config, [*SCAR_SECTIONS, "scar_diagnose"])
    settings = ScarDiagnoseSettings.from_config(config["scar_diagnose"])
    measured = read_measured_scar(args.measured[0])
    model = ScarModel.from_config(config)
    require_as_wide_as_the_contact(measured, model)
    print(f"fewear diagnose: {len(measured.names)} profile(s) of {measured.x_m.size} points "
          f"from {measured.source} against the believed {model.case} scar model; forward runs "
          "follow", file=sys.stderr, flush=True)
    diagnosis = diagnose_scar(measured, model, settings)
    summary = summarise(diagnosis, model.case,
                        {cause: model.coefficient_m2_N(cause) for cause in
                         (trial.cause for trial in diagnosis.trials)})
    with staged_output(args.out) as stage:
        write_outputs(diagnosis, summary, stage)
    for note in diagnosis.notes:
        print(f"fewear diagnose: {note}", file=sys.stderr)
    for entry in summary["candidates"]:
        print(f"fewear diagnose: {entry['cause']}: fitted x{entry['fitted_factor']:.4g} (folds "
              + ", ".join(f"{factor:.3g}" for factor in entry["fold_factors"])
              + f"), held-out RMS {entry['held_out_rms_m']['believed'] * 1e6:.3g} -> "
              f"{entry['held_out_rms_m']['fitted'] * 1e6:.3g} um, p {entry['p_value']:.2g} on "
              f"{entry['effective_observations']} effective observations, "
              f"{entry['forward_runs']} forward runs", file=sys.stderr)
    print_verdict(summary, args.out, unit=" m", confounded=[
        f"also accepted: {cause}" for cause in summary["confounded"]])
    return 0


def require_as_wide_as_the_contact(measured, model) -> None:
    """A worn scar is at least as wide as the unworn contact that wore it (2a, the believed
    model's Hertz line contact): a measured scar narrower than half of it has its positions in
    the wrong unit (x in m under x_mm), or is the scar of another contact."""
    from fewear.loop.scar import hertz_half_width_m
    from fewear.wear.scar import scar_depth_and_width_m

    contact_m = 2.0 * hertz_half_width_m(model.problem, model.settings.normal_force_N)
    for name, depth in zip(measured.names, measured.depth_m):
        _, width = scar_depth_and_width_m(measured.x_m, depth)
        if width < 0.5 * contact_m:
            raise FewearInputError(
                f"{measured.source}, profile {name}: the scar is {width:.3g} m wide, narrower "
                f"than half the {model.case} contact that wore it (2a = {contact_m:.3g} m, "
                "Hertz): positions in m under x_mm (1 mm = 1e-3 m)? or a config of another "
                "contact")
