"""The one way the hot loop is compiled.

`kernel` is numba's nopython compilation with the on-disk cache and without the
numba runtime (NRT). The kernels never allocate, and without the runtime numba
also drops the atomic reference counting it otherwise does on every array taken
out of the `System` and `Work` tuples: measured on the six-bar with A and B
clearances, one right-hand side evaluation fell from 5.6 µs to 2.3 µs and the
clearance forces from 1.8 µs to 0.23 µs. A kernel that tried to allocate fails
to compile rather than allocating silently, which also enforces the
allocation-free rule.
"""

import numba

kernel = numba.njit(cache=True, _nrt=False)
kernel_inline = numba.njit(cache=True, inline="always", _nrt=False)
