"""patchwork: Bezier and NURBS curves and surfaces, meshes, guaranteed-error tessellation and
certified queries, with numpy arrays in and out (docs/python.md).

    import patchwork as pw
    s = pw.read_bpt("data/teapot.bpt")
    t = pw.tessellate(s, relative_tolerance=1e-3)
    t.positions.shape, t.indices.shape, t.error_bound, t.measured_error
"""

from ._patchwork import *  # noqa: F401,F403  (the extension is the package's content)

__version__ = "@PROJECT_VERSION@"
