"""What the FE and boundary-integral models share: elasticity assembly and linear solvers, contact algorithms
and mesh-convergence certification.

elasticity2d    plane-strain elasticity (P1/P2, mixed u-p), condensation onto contact nodes (LU)
elasticity3d    3D elasticity (P1/P2 tetrahedra), AMG-preconditioned CG and direct solvers
frictionless    frictionless contact on a condensed system: primal-dual active set, penalty (load control)
coulomb         Coulomb friction on a condensed 2D system: semi-smooth Newton / primal-dual active set
rigid_indenter  a rigid analytic indenter on a meshed 3D body: active set and penalty with AMG-CG
two_body        two meshed 3D bodies, node-to-surface contact, active set
convergence     observed order and Richardson extrapolation
"""
