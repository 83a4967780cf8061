"""The report skeleton both data kinds share: the verdict of a diagnosis, in its summary
(``diagnosis.json``) and on the console."""

from __future__ import annotations

from typing import Any


def verdict(causes, meaning: str, confounded: list, baseline_error: float,
            extended_error: float) -> dict[str, Any]:
    """The summary's verdict: the causes named (in order), the first (``"none"`` without one),
    what it means, the causes confounded with it, and the held-out errors of the baseline and
    the extended model with the gain 1 - e_extended / e_baseline (0 and the baseline's error
    without a cause)."""
    return {
        "causes": list(causes),
        "cause": causes[0] if causes else "none",
        "cause_meaning": meaning,
        "confounded": confounded,
        "gain": 1.0 - extended_error / baseline_error if causes else 0.0,
        "held_out_error": {"baseline": baseline_error,
                           "extended": extended_error if causes else baseline_error},
    }


def print_verdict(summary: dict[str, Any], out, *, unit: str, confounded: list[str]) -> None:
    """The verdict on standard output: the causes and the held-out errors (each followed by
    ``unit``), where the outputs are, then one line per ``confounded`` sentence (each data kind
    words its own) and per unexplained trend."""
    error = summary["held_out_error"]
    print(f"fewear diagnose: causes {', '.join(summary['causes']) or 'none'}, held-out error "
          f"{error['baseline']:.3g}{unit} -> {error['extended']:.3g}{unit} "
          f"(gain {summary['gain']:.0%}); outputs in {out}")
    for sentence in confounded:
        print(f"fewear diagnose: {sentence}")
    for sentence in summary["unexplained"]:
        print(f"fewear diagnose: unexplained: {sentence}")
