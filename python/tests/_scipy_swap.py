"""A pytest plugin (``-p _scipy_swap``) that puts the package's names in scipy's place.

Loaded before scipy's ``interpolate/tests/test_bsplines.py`` is imported, it binds
``spline.BSpline``, ``spline.make_interp_spline``… in ``scipy.interpolate`` and in the private
modules the test file imports them from (``_bsplines``, ``_ndbspline``, ``_fitpack_repro``)
and in ``_fitpack_py`` (whose ``splev``… recognise a ``BSpline`` by that binding),
so the unmodified test file tests this package. A name the package does not have yet is
bound to a stub that raises ``NotImplementedError``: its tests fail instead of silently
running scipy's own code.
"""

import importlib

import spline

#: The names of scipy's B-spline API that the test file uses, with the modules holding them.
NAMES = (
    "BSpline",
    "make_interp_spline",
    "make_lsq_spline",
    "make_smoothing_spline",
    "NdBSpline",
    "make_ndbspl",
    "make_splrep",
    "make_splprep",
    "generate_knots",
)
MODULES = (
    "scipy.interpolate",
    "scipy.interpolate._bsplines",
    "scipy.interpolate._ndbspline",
    "scipy.interpolate._fitpack_repro",
    # splev, splint, sproot, insert, splder, splantider dispatch on isinstance(tck, BSpline)
    # with this module's binding, then call the object's own methods.
    "scipy.interpolate._fitpack_py",
    # PPoly.from_spline likewise.
    "scipy.interpolate._interpolate",
)


def _missing(name):
    def stub(*args, **kwargs):
        raise NotImplementedError(f"spline has no {name} yet")

    stub.__name__ = name
    return stub


def swap():
    """Binds the package's names (or stubs) in every module of ``MODULES`` that has them.

    scipy's test classes are decorated with ``make_xp_test_case(BSpline)``, which looks the
    object up in scipy's table of array-API capabilities: ours get scipy's entries.
    """
    from scipy._lib._array_api import xp_capabilities_table

    ours = {name: getattr(spline, name, None) or _missing(name) for name in NAMES}
    for module_name in MODULES:
        module = importlib.import_module(module_name)
        for name in NAMES:
            if hasattr(module, name):
                theirs = getattr(module, name)
                if theirs in xp_capabilities_table:
                    xp_capabilities_table[ours[name]] = xp_capabilities_table[theirs]
                setattr(module, name, ours[name])


swap()
