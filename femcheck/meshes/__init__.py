"""Gmsh builders, one module per body family, and the content-keyed mesh cache.

plane       2D plane-strain halves (block, cylinder) with matching contact nodes
plane_full  full 2D bodies mirrored from the halves (frictional line contact)
block       3D quarter blocks refined over a contact patch; shared 3D helpers and the mesh cache
coated      coated blocks (structured layer bonded to a graded substrate), 2D and 3D
srb_segments  ball / block and seed-000 roller and raceway segments for two-body contact
"""
