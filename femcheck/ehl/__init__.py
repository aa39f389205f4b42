"""Elastohydrodynamic lubrication (EHL) of a point / elliptical contact, steady and transient (seed 004 §2.3,
§2.6, App. A; Venner & Lubrecht 2000): dimensionless groups, lubricant laws, film, Reynolds operator with the
NU2 wedge/squeeze scheme, line relaxation, FAS/FMG multigrid and time marching. Specification:
``shared/specs/ehl-life.md`` part A."""
