"""One package per paper, split by role: ``scenario``, ``trials``, ``figures``, ``claims``.

Each package's ``__init__`` defines ``SLUG``, ``TITLE`` and
``reproduce(*, quick=False, runner=None)`` returning an :class:`eotrack.repro.Reproduction`;
``python -m eotrack.repro`` discovers them. Packages without ``reproduce`` (the capstone) are
compositions of the library, not paper reproductions.
"""
