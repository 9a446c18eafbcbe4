"""Figures the lint still fails, each with the helper who owns it (issue 23).

Only figures whose owners have not fixed them yet belong here; an owner who fixes a figure
deletes its line (the test then runs strictly). Keys: ``report:<slug>/<figure stem>`` for a
REPORT figure, ``case:<slug>.<function>`` for a figure function drawn by a lint case,
``nocase:<slug>.<function>`` for a public figure function that no REPORT figure and no case
draws yet, ``notebook:<notebook stem>`` for a notebook whose stored figures fail (or were stored
before the kernel recorded the lint's verdict: re-execute it).
"""

# measured by the lint on 2026-12-01 21:25 (comment: the rules each figure still fails)
XFAIL: dict[str, str] = {
}  # empty since 2026-12-02 02:30: every figure case, report figure and stored notebook figure passes
