"""``fewear config [--out FILE.toml]``: the embedded default config (TOML), on stdout or into a
new file (an existing file is never overwritten)."""

from __future__ import annotations

import argparse
import os
import sys

from fewear.errors import FewearInputError


def main(args: argparse.Namespace) -> int:
    """The embedded default config on stdout, or into a new file ``args.out``."""
    from fewear.io.config import default_config_text

    text = default_config_text()
    if args.out is None:
        sys.stdout.write(text)
        return 0
    if os.path.isdir(args.out):
        raise FewearInputError(f"cannot write {args.out}: it is a folder; `fewear config --out` "
                               "takes a file name (e.g. --out my_case.toml)")
    try:
        with open(args.out, "x") as handle:
            handle.write(text)
    except FileExistsError:
        raise FewearInputError(f"cannot write {args.out}: the file exists; `fewear config --out` "
                               "never overwrites a file: remove it or give another name") from None
    except OSError as exc:
        raise FewearInputError(f"cannot write {args.out}: {exc.strerror}") from None
    return 0
