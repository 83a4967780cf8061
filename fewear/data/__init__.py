"""Data sets shipped with fewear (the scripts that made the synthetic ones are in
``tests/data_makers``).

``STANDIN_PIN_ON_DISC_CSV``: SYNTHETIC pin-on-disc readings for CuZn25Al6Fe3Mn3 on 42CrMo, a
stand-in for the seed paper's unpublished tests (``tests/data_makers/make_standin_pin_on_disc.py``).
``RUNNING_IN_SYNTHETIC_CSV``: SYNTHETIC histories with a hidden running-in, for the diagnosis demo
(``tests/data_makers/make_running_in_pin_on_disc.py``).
``SINGH2016_AL_SIC_CSV``: REAL published pin-on-disc data, transcribed from K. K. Singh et al.,
Adv. Mater. Sci. Eng. 2016, Article ID 3813412 (CC BY; source, licence and transcription notes in
the file's header).
``FRETTING_MCCOLL2004_CSV``: REAL measured wear scar of a fretting test, cylinder on flat (185 N,
18,000 cycles), digitised from McColl, Ding & Leen, Wear 256 (2004) 1114-1127, Fig. 11a;
``BLOCK_ON_RING_CRUZADO2010_CSV``: REAL measured scars of three repeated block-on-ring tests (65 N,
0.5 m/s, 3,600 m), digitised from Cruzado, Zabala, Urchegui & Gomez, Rev. Metal. 46 (2010)
106-114, Fig. 12. Both by I. Llavori (github.com/illavori/LevelSetWear, BSD 3-Clause: licence,
commit and path in each file's header); columns x_mm and surface heights in um (negative: worn).
"""

from pathlib import Path

STANDIN_PIN_ON_DISC_CSV = Path(__file__).with_name("pin_on_disc_cuzn25al6fe3mn3_42crmo.csv")
RUNNING_IN_SYNTHETIC_CSV = Path(__file__).with_name("pin_on_disc_running_in_synthetic.csv")
SINGH2016_AL_SIC_CSV = Path(__file__).with_name("pin_on_disc_singh2016_al_sic.csv")
FRETTING_MCCOLL2004_CSV = Path(__file__).with_name("scar_fretting_mccoll2004.csv")
BLOCK_ON_RING_CRUZADO2010_CSV = Path(__file__).with_name("scar_block_on_ring_cruzado2010.csv")
