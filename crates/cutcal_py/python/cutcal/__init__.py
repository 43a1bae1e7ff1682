"""cutcal for Python: orthogonal cutting tests -> Johnson-Cook parameters, FE cards, predictions.

The work is done by cutcal's Rust library (the same code as the ``cutcal`` command line); this
package converts types only. Equations are those of "A thermomechanically motivated approach for
identification of flow stress properties in metal cutting" (the paper): the DPZD zone model of
Sec 3 (Eqs 1-12, the enhanced fixed point of Sec 3.5), the Johnson-Cook law (Eqs 14, 16) and the
identification objective (Eq 15); predictions use the extended Oxley model (Oxley 1989; Lalwani,
Mehta & Jain 2009).

Units are in the names: ``speed_m_min``, ``uncut_mm``, ``a_mpa``, ``temperature_c`` ...

Errors are raised as :class:`CutcalError` subclasses carrying the CLI's located message
(``file:line: field `name` = 'value': reason``).
"""

from __future__ import annotations

from typing import Any, Dict, Iterable, List, Optional, Sequence, Union

import numpy as np

from . import _cutcal
from ._cutcal import (
    CuttingTest,
    CutcalError,
    DiagnoseError,
    ExportError,
    IdentError,
    IdentifyResult,
    InputError,
    JcParams,
    Material,
    ModelError,
    diagnose,
    export,
    identify,
    joint,
    predict as _predict,
    render,
)

__version__ = _cutcal.__version__

__all__ = [
    "CuttingTest",
    "CutcalError",
    "DiagnoseError",
    "ExportError",
    "IdentError",
    "IdentifyResult",
    "InputError",
    "JcParams",
    "Material",
    "ModelError",
    "diagnose",
    "export",
    "identify",
    "joint",
    "predict",
    "predict_many",
    "read_tests",
    "render",
    "TEST_COLUMNS",
]

#: The columns of a test, in the test CSV's names and units.
TEST_COLUMNS = (
    "test",
    "speed_m_min",
    "uncut_mm",
    "width_mm",
    "rake_deg",
    "fc_n_per_mm",
    "ft_n_per_mm",
    "chip_mm",
    "t_int_c",
    "edge_radius_um",
    "flank_wear_mm",
    "order",
)


def _pandas():
    try:
        import pandas  # noqa: F401
    except ImportError:
        return None
    return pandas


def read_tests(path, as_frame: Optional[bool] = None):
    """Reads a test CSV with the CLI's reader (located errors, unit conversion).

    Returns a pandas DataFrame with the columns of :data:`TEST_COLUMNS` when pandas is installed
    (or ``as_frame=True``), else a list of :class:`CuttingTest`. Forces given as totals
    (``fc_n``, ``ft_n``) come back per unit width (``fc_n_per_mm``), as the library holds them.
    """
    tests = _cutcal.read_tests(path)
    pd = _pandas()
    if as_frame is None:
        as_frame = pd is not None
    if not as_frame:
        return tests
    if pd is None:
        raise ImportError("read_tests(as_frame=True) needs pandas")
    return pd.DataFrame([t.to_dict() for t in tests], columns=list(TEST_COLUMNS))


def _none_if_missing(v):
    if v is None:
        return None
    try:
        if v != v:  # NaN: pandas' missing value
            return None
    except TypeError:
        pass
    return v


def _as_tests(tests) -> List[CuttingTest]:
    """A CuttingTest, a list of them, or a DataFrame with the test columns -> list of CuttingTest."""
    if isinstance(tests, CuttingTest):
        return [tests]
    if hasattr(tests, "to_dict") and hasattr(tests, "columns"):
        rows = tests.to_dict("records")
        out = []
        for r in rows:
            kw = {k: _none_if_missing(r.get(k)) for k in TEST_COLUMNS if k in r}
            kw["test"] = str(kw["test"])
            out.append(CuttingTest(**kw))
        return out
    return list(tests)


def predict(material: Material, jc: JcParams, tests, work_temperature_c: Optional[float] = None,
            lalwani_ranges: bool = False, eta: Optional[float] = None, psi: Optional[float] = None,
            sharp: bool = False) -> Dict[str, Any]:
    """Extended Oxley prediction (Oxley 1989; Lalwani et al. 2009) of every test.

    ``tests``: a CuttingTest, a list of them or a DataFrame from :func:`read_tests`. Returns the
    document of ``cutcal predict --json``: ``rows`` with ``fc_n``, ``ft_n`` (over the width), ``tc_mm``,
    the measurements and % errors, and the full SI ``prediction`` (None and ``error`` where the
    solve found no solution). A test's stated edge radius and flank wear add the published edge
    (Waldorf et al. 1998) and wear-land (Smithey et al. 2001) forces unless ``sharp=True``.
    """
    return _predict(material, jc, _as_tests(tests), work_temperature_c=work_temperature_c,
                    lalwani_ranges=lalwani_ranges, eta=eta, psi=psi, sharp=sharp)


def predict_many(material: Material, jc: JcParams, speed_m_min, uncut_mm, width_mm, rake_deg,
                 edge_radius_um=None, flank_wear_mm=None, work_temperature_c: Optional[float] = None,
                 lalwani_ranges: bool = False) -> Dict[str, Any]:
    """Vectorised extended Oxley prediction over numpy arrays of conditions.

    The condition arrays (m/min, mm, mm, deg, and optionally the edge radius in um and the flank
    wear land in mm, NaN meaning "not stated") broadcast against each other. The tool terms are
    those of :func:`predict` (Waldorf et al. 1998 edge, Smithey et al. 2001 wear land). Conditions run in
    parallel in Rust with the GIL released. Returns a dict of ``numpy.ma.MaskedArray`` of the
    broadcast shape, named with units: ``fc_n``, ``ft_n`` (over the width), ``fc_n_per_mm``,
    ``ft_n_per_mm``, ``tc_mm``, ``t_ab_c``, ``t_int_c``, ``phi_deg``, ``c0``, ``delta``; entries
    without a solution are masked (never NaN). Also ``converged`` (bool array), ``errors`` (list of
    the reason per condition, None where converged, in C order) and ``rust_seconds`` (time spent in
    the Rust loop).
    """
    given = [speed_m_min, uncut_mm, width_mm, rake_deg]
    tool = [edge_radius_um, flank_wear_mm]
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in given + [t for t in tool if t is not None]))
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
    rest = iter(flat[4:])
    tool_flat = [None if t is None else next(rest) for t in tool]
    values, converged, errors, seconds = _cutcal._predict_many(
        material, jc, *flat[:4], edge_radius_um=tool_flat[0], flank_wear_mm=tool_flat[1],
        work_temperature_c=work_temperature_c, lalwani_ranges=lalwani_ranges)
    mask = ~converged.reshape(shape)
    out: Dict[str, Any] = {k: np.ma.masked_array(v.reshape(shape), mask=mask) for k, v in values.items()}
    out["converged"] = converged.reshape(shape)
    out["errors"] = errors
    out["rust_seconds"] = seconds
    return out
