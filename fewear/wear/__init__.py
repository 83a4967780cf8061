"""Archard wear (seed eq. 10) and its wear coefficient k(p, v).

- ``fewear.wear.coefficient``: the wear coefficient models, constant or the seed's RBF network
  (eq. 9) fitted to pin-on-disc tests, saved and loaded as the ``[wear]`` config section.
"""
