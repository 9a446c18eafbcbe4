"""What a filter did at one frame."""

from __future__ import annotations

from enum import IntEnum

__all__ = ["FilterMode"]


class FilterMode(IntEnum):
    """What a filter did at one frame (eqs. 44–46)."""

    UPDATE = 0      #: C_k ≥ τ_h: standard update
    INFLATED = 1    #: τ_l ≤ C_k < τ_h: update with R̃ = λ R
    PREDICT = 2     #: C_k < τ_l or no star: prediction only, growing Q

