"""The command line's subcommands, one module each: each parses its arguments and the config at
the edge, calls the library (the same functions as :mod:`fewear.api`) and writes the outputs.

The entry point and the argument parser are :mod:`fewear.cli`. Nothing below the commands imports
them.
"""
