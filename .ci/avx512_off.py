"""Print the environment that switches this host's AVX-512 code paths off (for .ci/run).

Output: ``NAME=value`` lines on stdout (nothing when the host has no AVX-512), a human summary
on stderr. Read from the libraries themselves:

- numpy: ``NPY_DISABLE_CPU_FEATURES`` accepts only the build's *dispatch targets* (numpy 2.4:
  ``X86_V3 X86_V4 AVX512_ICL AVX512_SPR``; naming a plain feature such as ``AVX512F`` prints
  "You cannot disable CPU features ... not part of the dispatched optimizations" and disables
  nothing). We list the AVX-512 targets (``X86_V4``, ``AVX512_*``; ``AVX512F``... on older
  numpy) that are in the dispatch list *and* available on this host.
- OpenBLAS (numpy's and scipy's bundled copies, DYNAMIC_ARCH): ``OPENBLAS_CORETYPE=Haswell``
  when the core it picked is an AVX-512 one (SkylakeX, Cooperlake, SapphireRapids).
- OpenCV: ``OPENCV_CPU_DISABLE`` with the AVX-512 features it dispatches to on this host.
"""

from __future__ import annotations

import ctypes
import glob
import os
import sys

import numpy as np

try:
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
except ImportError:  # numpy < 2
    from numpy.core._multiarray_umath import __cpu_dispatch__, __cpu_features__


def _is_avx512(name: str) -> bool:
    return "AVX512" in name or name == "X86_V4"


def numpy_targets() -> list[str]:
    return [t for t in __cpu_dispatch__ if _is_avx512(t) and __cpu_features__.get(t)]


def openblas_core() -> str | None:
    libs = sorted(glob.glob(os.path.join(os.path.dirname(np.__file__), os.pardir,
                                         "numpy.libs", "libscipy_openblas*")))
    for path in libs:
        lib = ctypes.CDLL(path)
        for fn in ("scipy_openblas_get_corename64_", "scipy_openblas_get_corename",
                   "openblas_get_corename64_", "openblas_get_corename"):
            f = getattr(lib, fn, None)
            if f is not None:
                f.restype = ctypes.c_char_p
                return f().decode()
    return None


def opencv_features() -> list[str]:
    try:
        import cv2
    except ImportError:
        return []
    # "SSE SSE2 SSE3 *SSE4.1 ... *AVX2 *AVX512-SKX": '*' dispatched, trailing '?' unavailable
    return [f[1:] for f in cv2.getCPUFeaturesLine().split()
            if f.startswith("*") and not f.endswith("?") and "AVX512" in f]


def main() -> int:
    host = [k for k, v in __cpu_features__.items() if v and "AVX512" in k]
    print(f"host AVX-512 features (numpy): {' '.join(host) or 'none'}", file=sys.stderr)
    env = {}
    targets = numpy_targets()
    if targets:
        env["NPY_DISABLE_CPU_FEATURES"] = " ".join(targets)
    core = openblas_core()
    if core and core.lower() in {"skylakex", "cooperlake", "sapphirerapids"}:
        env["OPENBLAS_CORETYPE"] = "Haswell"
    cv = opencv_features()
    if cv:
        env["OPENCV_CPU_DISABLE"] = ",".join(cv)
    print(f"numpy dispatch targets {list(__cpu_dispatch__)}; OpenBLAS core {core}; "
          f"OpenCV AVX-512 paths {cv or 'none'}", file=sys.stderr)
    for k, v in env.items():
        print(f"{k}={v}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
