"""Rolling contact with friction (Kalker's exact theory, CECT core): influence coefficients, normal and
tangential solvers on a planar contact grid, strip theory, FASTSIM, linear theory and full slip."""
