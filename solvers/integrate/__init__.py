"""Integrators: Runge-Kutta tableaux, Gauss collocation, the Taylor backend, batches,
work-precision data."""
