"""Figures the lint still fails, each with the helper who owns it (issue 23).

Only figures whose owners have not fixed them yet belong here; an owner who fixes a figure
deletes its line (the test then runs strictly). Keys: ``report:<slug>/<figure stem>`` for a
REPORT figure, ``case:<slug>.<function>`` for a figure function drawn by a lint case,
``nocase:<slug>.<function>`` for a public figure function that no REPORT figure and no case
draws yet.
"""

XFAIL: dict[str, str] = {
}
