"""Data sets shipped with fewear, and the scripts that made them.

``STANDIN_PIN_ON_DISC_CSV``: SYNTHETIC pin-on-disc readings for CuZn25Al6Fe3Mn3 on 42CrMo, a
stand-in for the seed paper's unpublished tests (see ``make_standin_pin_on_disc.py``).
"""

from pathlib import Path

STANDIN_PIN_ON_DISC_CSV = Path(__file__).with_name("pin_on_disc_cuzn25al6fe3mn3_42crmo.csv")
