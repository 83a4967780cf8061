"""The joint-load history of the recorded crank cycle(s): what the wear stage consumes.

One row per accepted time step (the steps are variable when the step-size control is on: resample
with ``np.interp`` on ``time_s`` or ``crank_angle_rad``; the crank angle is theta0 + omega t, not
wrapped, so it increases through the recorded cycles). The first row is the state at the start of
the recorded cycles. Vectors are in the bushing body's frame, which turns with it (the slider's:
x along the slide, y normal to it, for the slider-crank the global frame; a four-bar rocker's:
x along the rocker). For a flexible rod the pin's angular velocity is that of the end node's
cross-section (the direction of r_,y). For a general mechanism (:mod:`fewear.mbd.mechanism`),
the crank angle is the first driver's body angle and ``slider_x_m``, ``slider_velocity_m_s``
are the bushing body's x and x'.

Sign conventions. The eccentricity e = r_pin - r_bushing (pin centre relative to the bushing
centre). ``reaction_force_N`` is the force exerted BY the bushing (slider) ON the pin (connecting
rod); in contact it is -F_n n + F_t t with n = e/|e| and t = k x n, so ``normal_force_N`` F_n >= 0
pushes the pin back to the centre and ``friction_force_N`` F_t is its component along t.
``rel_omega_rad_s`` is the angular velocity of the pin (rod end) minus that of the bushing.

Modes (``mode``: 0, 1, 2 = ``MODES``):
- ``free`` (0): no contact force (F_n = 0: penetration <= 0, or the surfaces separating faster
  than the Lankarani-Nikravesh damping allows, where the law's force is clipped at zero);
- ``impact`` (1): a step of a contact episode (a maximal run of steps with F_n > 0) that
  lasts at most ``impact_max_duration_s``: a collision followed by rebound;
- ``contact`` (2): a step of a longer episode: the pin stays on the wall (continuous contact).
For the ideal joint every step is ``contact``, the eccentricity and penetration are zero and F_n
is the magnitude of the reaction (friction zero).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MODES = ("free", "impact", "contact")


@dataclass(frozen=True)
class JointHistory:
    """Per-step joint quantities (n steps; SI units, see the module docstring)."""

    time_s: np.ndarray
    crank_angle_rad: np.ndarray
    slider_x_m: np.ndarray
    slider_velocity_m_s: np.ndarray
    eccentricity_m: np.ndarray  # (n, 2)
    penetration_m: np.ndarray
    normal_force_N: np.ndarray
    friction_force_N: np.ndarray
    reaction_force_N: np.ndarray  # (n, 2)
    rel_omega_rad_s: np.ndarray
    mode: np.ndarray  # int, index into MODES

    @property
    def n_steps(self) -> int:
        return int(self.time_s.size)

    @property
    def impacts(self) -> int:
        """The number of contact episodes classified as impacts."""
        return len(self.impact_episodes())

    def impact_episodes(self) -> list[tuple[int, int]]:
        """(first, last) rows of each impact episode (:func:`impact_episodes`)."""
        return impact_episodes(self.mode)

    @property
    def peak_contact_force_N(self) -> float:
        return float(np.max(np.linalg.norm(self.reaction_force_N, axis=1), initial=0.0))

    def load_slip_by_direction(self, pin_radius_m: float,
                               sector_deg: float) -> tuple[np.ndarray, np.ndarray]:
        """Where the pin slides under load: the load-slip F_n R_pin |omega_rel| dt (J, the
        product Archard's worn volume grows with) of the history, gathered by the direction of
        the pin's eccentricity (bushing frame) into sectors of ``sector_deg`` from 0 deg.
        Returns (the load-slip per sector (J), the sectors' edges (deg, 0 to 360))."""
        dt = np.diff(self.time_s, prepend=self.time_s[0])
        load_slip = self.normal_force_N * pin_radius_m * np.abs(self.rel_omega_rad_s) * dt
        direction_deg = np.degrees(np.arctan2(self.eccentricity_m[:, 1],
                                              self.eccentricity_m[:, 0])) % 360.0
        return np.histogram(direction_deg, bins=round(360.0 / sector_deg), range=(0.0, 360.0),
                            weights=load_slip)


def impact_episodes(mode: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) rows of each impact episode (a maximal run of impact-mode rows, ``mode`` 1)
    of a ``mode`` array."""
    impact = np.concatenate([[False], np.asarray(mode) == 1, [False]])
    starts = np.flatnonzero(impact[1:] & ~impact[:-1])
    ends = np.flatnonzero(~impact[1:] & impact[:-1]) - 1
    return list(zip(starts.tolist(), ends.tolist()))


def classify_modes(time_s: np.ndarray, normal_force_N: np.ndarray,
                   impact_max_duration_s: float) -> np.ndarray:
    """The ``mode`` array of the module docstring from the normal-force history.

    An episode's duration is measured from the step before its first contact step to its last
    contact step (the contact began within that step)."""
    in_contact = normal_force_N > 0.0
    mode = np.zeros(time_s.size, dtype=int)
    edges = np.diff(np.concatenate([[0], in_contact.astype(int), [0]]))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    for start, end in zip(starts, ends):
        begin_time = time_s[start - 1] if start > 0 else time_s[start]
        duration = time_s[end - 1] - begin_time
        mode[start:end] = 1 if duration <= impact_max_duration_s else 2
    return mode


def loaded_sectors(load_slip_J: np.ndarray, share: float) -> list[int]:
    """The loaded arc: the indices (ascending) of the fullest sectors of ``load_slip_J``
    (:meth:`JointHistory.load_slip_by_direction`) that together hold ``share`` of it."""
    fullest = np.argsort(load_slip_J)[::-1]
    held = np.cumsum(load_slip_J[fullest]) / load_slip_J.sum()
    return sorted(int(sector) for sector in fullest[:int(np.searchsorted(held, share)) + 1])
