"""``fegear cache``: the model cache (:mod:`fegear.toothpair.ring.cache`, the meshed and
condensed ring models kept for later runs): where it is, what it holds, and ``--clear`` to
empty it."""

from __future__ import annotations

import argparse


def add_parser(sub) -> None:
    p = sub.add_parser("cache", help="the model cache (the meshed and condensed models kept "
                                     "for later runs): list or clear it")
    p.add_argument("--clear", action="store_true", help="remove every entry")


#: the cap as the help states it (:mod:`fegear.toothpair.ring.cache`: ENV_CAP, CAP_GB; no
#: import here, for a quick --help: tests/cli/test_cache_cli.py pins the two)
CAP_TEXT = "FEGEAR_CACHE_GB (2 GB unless set)"


def add_switch(p, default: bool) -> None:
    """``--cache`` / ``--no-cache`` on a solving command (or a group of its options) whose
    own default is ``default``."""
    g = p.add_mutually_exclusive_group()
    state = "on" if default else "off"
    g.add_argument("--cache", dest="cache", action="store_const", const=True, default=None,
                   help="read the meshed and condensed models from the model cache where an "
                        "earlier run kept them, and keep them there: a model is about 140 MB "
                        "at standard (60 coarse, 90 fast, 430 fine), and the error estimate "
                        "keeps its level's model too, so one `fegear solve --cache` writes "
                        "about 220 MB (150 at coarse or fast, 540 at fine). The folder is held "
                        "under "
                        f"{CAP_TEXT}, the least recently used going first; `fegear cache` lists "
                        f"and clears it ({state} by default here, FEGEAR_CACHE=on|off sets the "
                        "default)")
    g.add_argument("--no-cache", dest="cache", action="store_const", const=False,
                   help="neither read nor keep models in the model cache")


def apply_switch(a: argparse.Namespace, default: bool) -> None:
    """Turn the model cache on or off for this command and the workers it starts: the
    option given, else FEGEAR_CACHE, else the command's ``default``. With it on, a bad
    size cap is refused now, before any work."""
    from ..toothpair.ring import cache

    on = a.cache if a.cache is not None else cache.setting()
    cache.use(default if on is None else on)
    if cache.enabled():
        cache.cap_bytes()


def run(a: argparse.Namespace) -> int:
    import time

    from ..toothpair.ring import cache

    folder = cache.directory()
    if a.clear:   # whatever the cap says: a bad one must not keep the folder from emptying
        n, size = cache.clear()
        print(f"removed {n} entries ({size / 1e6:.0f} MB) from {folder}")
        return 0
    cap = cache.cap_bytes()
    rows = cache.entries()
    total = sum(size for _, size, _ in rows)
    print(f"{folder}: {len(rows)} entries, {total / 1e6:.0f} MB of {cap / 1e9:g} GB "
          f"({cache.ENV_CAP}; the least recently used go first)")
    for path, size, used in reversed(rows):
        print(f"  {path.name}  {size / 1e6:6.0f} MB  last used "
              f"{time.strftime('%Y-%m-%d %H:%M', time.localtime(used))}")
    print(f"on for `fegear study` and `fegear relief` (--no-cache), off for `fegear solve` "
          f"(--cache); {cache.ENV}=on|off sets it for any command")
    return 0
