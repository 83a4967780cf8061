"""Resolution first: the believed model's wear blocks refined until its own noise (runs started a
degree apart, halved wear steps) is at most the instrument's scatter, before any cause is fitted.
The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import copy
import math
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np

from fewear.diagnose.joint import structure
from fewear.diagnose.joint.candidates import Candidate
from fewear.diagnose.joint.fitting import Fit, Observations, offset_fit, offset_start
from fewear.diagnose.joint.forward import (
    WearHistory,
    model_config,
    simulate_wears,
    started_later,
    with_doubled_recorded_cycles,
    with_halved_wear_steps,
)

MEMBER_START_OFFSETS_DEG = (1.0, 2.0)
"""Crank angles (deg) by which the runs that measure the believed model's spread start later."""


@dataclass(frozen=True)
class WearStepLevel:
    """One level of the wear blocks: its adaptive bound ``max_depth_increment_fraction`` and
    ``max_extrapolation_factor`` (or fixed ``extrapolation_factor``), the spread of the runs
    started later (m RMS; None on a level verified by one run, :func:`_verified_by_one_run`)
    and how far their mean bore moved from the level before (m RMS; None on the first level; on
    a level of one run, its upper estimate)."""

    blocks: dict[str, float]
    spread_rms_m: float | None
    change_from_coarser_rms_m: float | None


def baseline_fit(name: str, run: WearHistory, obs: Observations, max_offset_deg: float) -> Fit:
    """The model of one run fitted with its angular offset only (the level of k as run)."""
    start = offset_start(obs, Candidate(name, (run,)), max_offset_deg)
    return offset_fit(name, run, obs, start, max_offset_deg)


def resolve_wear_step(config: dict, obs: Observations, max_halvings: int,
                      max_offset_deg: float) -> tuple[dict, dict[str, Any]]:
    """(the believed ``config`` at the coarsest wear blocks its noise allows, the resolution)
    by the rule of the method notes. The resolution (JSON-ready): ``instrument_scatter_m`` (from
    neighbouring profile points of the residuals of the user's model,
    :func:`fewear.diagnose.joint.structure.scatter_estimate_m`; None without profiles, and then
    the user's blocks are kept), ``wear_step_levels`` (every level measured), the chosen level's
    ``start_angle_spread_rms_m`` and ``halved_blocks_rms_m`` (the next level's move), and
    ``doubled_recorded_cycles_rms_m`` (its bore with twice the crank cycles recorded per block:
    the sampling of the orbit); ``out_of_reach``: the ladder stopped by :func:`_out_of_reach`."""
    rod = config["wear_loop"]["rod_models"][0]
    counts = np.unique(obs.cycles)
    level_config = model_config(config, rod, int(obs.cycles.max()) + 1)
    members = [_members(level_config)]
    first = baseline_fit("baseline", members[0][0], obs, max_offset_deg)
    scatter = structure.scatter_estimate_m(obs.angle_rad, first.residuals_m, obs.cycles)
    levels, configs, means, out_of_reach = [], [level_config], [], False
    for halving in range(max_halvings + 2):
        bores = np.array([run.nodal_depths_m(counts) for run in members[-1]])
        means.append(bores.mean(axis=0))
        change = None if halving == 0 else _rms(means[-1] - means[-2])
        levels.append(WearStepLevel(_blocks(configs[-1]), _spread(bores), change))
        _say(_level_line(halving, levels[-1], scatter, members[-1], max_halvings))
        if halving == 0 and scatter is None:
            break
        if halving > 0 and (_resolved(levels[-2], change, scatter) or halving > max_halvings):
            break
        out_of_reach = _out_of_reach(levels[-1], scatter, max_halvings - halving)
        if out_of_reach:
            _say(f"fewear diagnose: resolution stops at level {halving + 1}: its runs part by "
                 f"more than the {max_halvings - halving} halvings left could bring within the "
                 "scatter even if each halved it; the diagnosis runs at this level, its noise "
                 "the limit")
            break
        configs.append(with_halved_wear_steps(configs[-1]))
        verified = _verified_by_one_run(configs[-1], configs[-2], means[-1], levels[-1],
                                        counts, scatter)
        if verified is not None:
            levels.append(verified)
            _say(_verified_line(halving + 1, verified, scatter, max_halvings))
            break
        members.append(_members(configs[-1], _doubled(configs[-2])))
    chosen = _chosen_level(levels, scatter, max_halvings)
    doubled, = simulate_wears([_doubled(configs[chosen])])
    resolved = _with_blocks(config, levels[chosen].blocks)
    next_move = levels[chosen + 1].change_from_coarser_rms_m if chosen + 1 < len(levels) else None
    return resolved, {
        "instrument_scatter_m": scatter,
        "wear_step_levels": [vars(level) for level in levels],
        "wear_step": levels[chosen].blocks,
        "out_of_reach": out_of_reach,
        "resolved": bool(scatter is not None and next_move is not None
                         and _resolved(levels[chosen], next_move, scatter)),
        "start_angle_spread_rms_m": levels[chosen].spread_rms_m,
        "halved_blocks_rms_m": next_move if next_move is not None else math.nan,
        "doubled_recorded_cycles_rms_m": _rms(doubled.nodal_depths_m(counts)
                                              - members[chosen][0].nodal_depths_m(counts))}


def model_noise_m(resolution: dict[str, Any]) -> float:
    """The believed model's own noise at its chosen level: the larger of the runs' spread and
    the move of halved blocks (0 where not measured)."""
    noise = [resolution.get("start_angle_spread_rms_m"), resolution.get("halved_blocks_rms_m")]
    return max([value for value in noise if value is not None and math.isfinite(value)],
               default=0.0)


def _resolved(level: WearStepLevel, next_change_m: float, scatter_m: float | None) -> bool:
    """A level is resolved when its runs' spread and the next level's move of their mean are
    both at most the instrument's scatter."""
    return scatter_m is not None and max(level.spread_rms_m, next_change_m) <= scatter_m


def _out_of_reach(level: WearStepLevel, scatter_m: float | None, halvings_left: int) -> bool:
    """Whether the halvings left cannot bring the runs' spread within the scatter even if each
    halved it (a first-order wear step's error does; the spread of a chaotic orbit's runs need
    not fall at all): data more precise than any affordable model (a model's own output as the
    data, scatter 0.003 um against runs 0.5 um apart) would otherwise have the ladder halve the
    wear steps to the last level, each twice as dear, for a model no more resolved. With no
    halving left, the next level is still run, to measure its move."""
    return (scatter_m is not None and halvings_left >= 1
            and level.spread_rms_m > 2.0**halvings_left * scatter_m)


def _chosen_level(levels: list[WearStepLevel], scatter_m: float | None,
                  max_halvings: int) -> int:
    """The coarsest resolved level, else the finest one allowed (at most ``max_halvings``)."""
    for index in range(len(levels) - 1):
        if _resolved(levels[index], levels[index + 1].change_from_coarser_rms_m, scatter_m):
            return index
    return min(len(levels) - 1, max_halvings)


def _verified_by_one_run(config: dict, coarser: dict, coarser_mean_m: np.ndarray,
                         coarser_level: WearStepLevel, counts: np.ndarray,
                         scatter_m: float | None) -> WearStepLevel | None:
    """The level of ``config`` (the ``coarser`` one's blocks halved) measured by its run from the
    config's crank angle alone, when that is enough to resolve the coarser level: the coarser
    level's spread is within the scatter and the run's RMS distance from its mean bore
    (``coarser_mean_m``, counts by nodes), an upper estimate of the move, is too. None
    otherwise (the run is kept: the level's full measurement reuses it). The run is made beside
    the coarser level's doubled recorded cycles (needed: that level is then chosen)."""
    if not _resolved(coarser_level, 0.0, scatter_m):  # its spread alone already rules it out
        return None
    run, _ = simulate_wears([(config, f"believed model, {_blocks_text(_blocks(config))}"),
                             _doubled(coarser)])
    move_bound = _rms(run.nodal_depths_m(counts) - coarser_mean_m)
    if not _resolved(coarser_level, move_bound, scatter_m):
        return None
    return WearStepLevel(_blocks(config), None, move_bound)


def _verified_line(halving: int, level: WearStepLevel, scatter_m: float,
                   max_halvings: int) -> str:
    """What a level verified by one run (:func:`_verified_by_one_run`) found."""
    return (f"{_level_heading(halving, level, max_halvings)}: its run from the config's crank "
            f"angle lies {level.change_from_coarser_rms_m * 1e6:.3g} um from the level before's "
            f"mean (an upper estimate of the move), within the instrument's scatter "
            f"{scatter_m * 1e6:.3g} um: the level before is resolved, this one's other runs are "
            "not made")


def _members(config: dict, beside: tuple[dict, str] | None = None) -> list[WearHistory]:
    """Runs of ``config`` whose crank starts 0 and :data:`MEMBER_START_OFFSETS_DEG` later, side
    by side, and the run ``beside`` with them: the level before's :func:`_doubled` run, which
    is needed if that level is chosen (decided by these runs) and otherwise fills the core the
    three runs leave idle on a two-core machine."""
    blocks = _blocks_text(_blocks(config))
    requests = [(config, f"believed model, {blocks}")]
    for offset in MEMBER_START_OFFSETS_DEG:
        requests.append((started_later(config, offset),
                         f"believed model, {blocks}, started {offset:g} deg later"))
    return simulate_wears(requests + ([beside] if beside else []))[:len(requests)]


def _say(line: str) -> None:
    """``line`` on stderr, once (rank 0): what the resolution is doing, while it runs."""
    from fewear.parallel import launcher_rank_and_size

    if launcher_rank_and_size()[0] == 0:
        print(line, file=sys.stderr, flush=True)


def _level_line(halving: int, level: WearStepLevel, scatter_m: float | None,
                runs: list[WearHistory], max_halvings: int) -> str:
    """A level's noise against the scatter and what its runs cost: a user whose model is dear
    sees it before the next level (each twice as dear) runs."""
    moved = ("" if level.change_from_coarser_rms_m is None else
             f", their mean moved {level.change_from_coarser_rms_m * 1e6:.3g} um from the level "
             "before")
    against = ("no scatter to compare with (no profiles): the config's wear steps are kept"
               if scatter_m is None else f"the instrument's scatter {scatter_m * 1e6:.3g} um")
    seconds = sum(run.wall_time_s for run in runs) / len(runs)
    return (f"{_level_heading(halving, level, max_halvings)}: runs started "
            f"0-{MEMBER_START_OFFSETS_DEG[-1]:g} deg later part by "
            f"{level.spread_rms_m * 1e6:.3g} um{moved}; {against}; {seconds:.0f} s a run "
            "(a level finer: about twice that)")


def _level_heading(halving: int, level: WearStepLevel, max_halvings: int) -> str:
    """The start of a level's progress line: its number (``halving`` + 1) and wear steps."""
    return (f"fewear diagnose: resolution, level {halving + 1} of at most {max_halvings + 2} "
            f"({_blocks_text(level.blocks)})")


def _doubled(config: dict) -> tuple[dict, str]:
    """The run of ``config`` with twice the recorded cycles (the resolution's
    ``doubled_recorded_cycles_rms_m``)."""
    return (with_doubled_recorded_cycles(config), "believed model, recorded cycles doubled")


_BLOCK_KEYS = {"adaptive": ("max_depth_increment_fraction", "max_extrapolation_factor"),
               "fixed": ("extrapolation_factor",)}


def _blocks(config: dict) -> dict[str, float]:
    """The settings of ``config`` that :func:`with_halved_wear_steps` changes."""
    loop = config["wear_loop"]
    return {**{key: float(loop[key]) for key in _BLOCK_KEYS[loop["extrapolation"]]},
            "wear_steps_per_block": int(loop["wear_steps_per_block"])}


def _blocks_text(blocks: dict[str, float]) -> str:
    """The wear-step settings ``blocks`` as the progress lines name them."""
    return ", ".join(f"{key} = {value:g}" for key, value in blocks.items())


def _with_blocks(config: dict, blocks: dict[str, float]) -> dict:
    changed = copy.deepcopy(config)
    changed["wear_loop"].update(blocks)
    return changed


def _spread(bores: np.ndarray) -> float:
    """RMS deviation of the runs' bores (runs, counts, nodes) about their mean (sample, n - 1)."""
    deviation = bores - bores.mean(axis=0)
    return float(np.sqrt(np.mean(deviation**2) * len(bores) / (len(bores) - 1)))


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.asarray(values) ** 2)))
