"""One module per paper: scenario, experiment run, figures and tables, claim evaluation.

Each module defines ``SLUG``, ``TITLE`` and ``reproduce(*, quick=False, runner=None)`` returning
an :class:`eotrack.repro.Reproduction`; ``python -m eotrack.repro`` discovers them.
"""
