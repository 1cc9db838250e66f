"""One place that decides how kernels are compiled: `kernel`, the decorator of every
compiled function of solvers/kernels.

Importing it installs numba's cache as this project uses it (solvers/kernels/numba_cache.py:
the package's content-hash stamp, and a disk that cannot be read or written costing a
compile, not the run), before any kernel is defined.
"""

import numba

from solvers.kernels import numba_cache

numba_cache.install()

# cache=True writes the machine code next to the sources (__pycache__), so a second
# process loads it instead of compiling. error_model="numpy": 1/0 gives inf, no
# Python exception path in the hot loop; fastmath stays off (we compare to round-off).
kernel = numba.njit(cache=True, error_model="numpy", nogil=True)
