"""Figures the lint still fails, each with the helper who owns it (issue 23).

Only figures whose owners have not fixed them yet belong here; an owner who fixes a figure
deletes its line (the test then runs strictly). Keys: ``report:<slug>/<figure stem>`` for a
REPORT figure, ``case:<slug>.<function>`` for a figure function drawn by a lint case,
``nocase:<slug>.<function>`` for a public figure function that no REPORT figure and no case
draws yet, ``notebook:<notebook stem>`` for a notebook whose stored figures fail (or were stored
before the kernel recorded the lint's verdict: re-execute it).
"""

# flagged by the rules added on 2026-12-02 06:10 (multi-line/outlined text, clipped text,
# bars/scatter lists/bands, deuteranopia pairs, 1e−03 labels); requests to the owners in
# /tmp/coord/requests/fig-<slug>.md (comment: the rules each figure still fails)
XFAIL: dict[str, str] = {
}
