"""Data sets shipped with fewear, and the scripts that made them.

``STANDIN_PIN_ON_DISC_CSV``: SYNTHETIC pin-on-disc readings for CuZn25Al6Fe3Mn3 on 42CrMo, a
stand-in for the seed paper's unpublished tests (see ``make_standin_pin_on_disc.py``).
``RUNNING_IN_SYNTHETIC_CSV``: SYNTHETIC histories with a hidden running-in, for the diagnosis demo
(see ``make_running_in_pin_on_disc.py``).
``SINGH2016_AL_SIC_CSV``: REAL published pin-on-disc data, transcribed from K. K. Singh et al.,
Adv. Mater. Sci. Eng. 2016, Article ID 3813412 (CC BY; source, licence and transcription notes in
the file's header).
"""

from pathlib import Path

STANDIN_PIN_ON_DISC_CSV = Path(__file__).with_name("pin_on_disc_cuzn25al6fe3mn3_42crmo.csv")
RUNNING_IN_SYNTHETIC_CSV = Path(__file__).with_name("pin_on_disc_running_in_synthetic.csv")
SINGH2016_AL_SIC_CSV = Path(__file__).with_name("pin_on_disc_singh2016_al_sic.csv")
