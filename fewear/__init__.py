"""fewear: finite-element wear workbench for revolute clearance joints.

Stages (one subpackage each, data passed between them as frozen dataclasses in SI units):

- :mod:`fewear.mbd`        planar multibody dynamics (NumPy): rigid and ANCF bodies, clearance joint
- :mod:`fewear.contact`    bushing contact model (DOLFINx + PETSc), pressures and slips on the bore
- :mod:`fewear.wear`       Archard wear law and the wear coefficient k(p, v)
- :mod:`fewear.mesh`       bushing meshes (gmsh), ALE motion and re-meshing
- :mod:`fewear.diagnose`   measured data, diagnosis of what the model gets wrong
- :mod:`fewear.io`         configuration, outputs
- :mod:`fewear.plot`       figures (matplotlib; PyVista imported lazily)

Only modules that need DOLFINx import it.
"""

__version__ = "0.1.0"
