"""One place that decides how kernels are compiled."""

import numba

# cache=True writes the machine code next to the sources (__pycache__), so a second
# process loads it instead of compiling. error_model="numpy": 1/0 gives inf, no
# Python exception path in the hot loop; fastmath stays off (we compare to round-off).
kernel = numba.njit(cache=True, error_model="numpy", nogil=True)
