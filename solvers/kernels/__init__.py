"""Compiled kernels: numba functions of floats, ints and arrays only.

They know nothing of bodies, cases or the web app; the Python layer converts at the
boundary. Every function is written so that the same source also runs on complex
arrays (complex-step derivatives) and, with NUMBA_DISABLE_JIT=1, as plain Python.
"""
