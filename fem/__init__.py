"""scikit-fem contact solvers and post-processing (3D elasticity, unilateral contact)."""
