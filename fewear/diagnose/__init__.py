"""``fewear diagnose``: what a wear model gets wrong on measured data, which physical cause
explains it, and how much better the extended model predicts what it has not seen.

- :mod:`fewear.diagnose.core`        the method the three data kinds share (causes, statistics)
- :mod:`fewear.diagnose.tribometer`  pin-on-disc tests: plain Archard against the readings
- :mod:`fewear.diagnose.joint`       wear measured on the joint: the believed config against it
- :mod:`fewear.diagnose.scar`        a measured wear scar: `fewear scar`'s case against it

The command (:mod:`fewear.commands.diagnose`) dispatches on the data kind.
"""
