# Type stubs of the native module cutcal._cutcal (Rust, PyO3). Units are in the names.
from os import PathLike
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike]

__version__: str

class CutcalError(Exception): ...
class InputError(CutcalError):
    """Malformed or out-of-range input; the message is the CLI's `file:line: field ...`."""
class ModelError(CutcalError): ...
class IdentError(CutcalError): ...
class ExportError(CutcalError): ...
class DiagnoseError(CutcalError): ...

class Material:
    """A workpiece material: Table 3 polynomials (paper), bounds, interface (Eq 17 friction)."""
    def __init__(self, toml_text: Optional[str] = None, source: str = "<Material>", **keys: Any) -> None:
        """TOML text of a material file, or the file's keys as keywords (same reader as from_toml)."""
    @staticmethod
    def from_toml(path: _Path) -> Material: ...
    @property
    def name(self) -> str: ...
    @property
    def melting_c(self) -> float: ...
    @property
    def room_c(self) -> float: ...
    @property
    def path(self) -> str: ...

class JcParams:
    """Johnson-Cook set, paper Eqs 14 and 16: A, B in MPa; temperatures in degC."""
    def __init__(self, a_mpa: float, b_mpa: float, n: float, c: float, m: float, tm_c: float,
                 tr_c: float = 20.0, eps0_per_s: float = 1.0) -> None: ...
    @staticmethod
    def from_toml(path: _Path) -> JcParams: ...
    a_mpa: float
    b_mpa: float
    n: float
    c: float
    m: float
    eps0_per_s: float
    tm_c: float
    tr_c: float
    def flow_stress_mpa(self, strain: float, strain_rate_per_s: float, temperature_c: float) -> float:
        """Paper Eq 16."""
    def to_dict(self) -> Dict[str, float]: ...

class CuttingTest:
    """One orthogonal test in the test CSV's columns and units."""
    def __init__(self, test: str, speed_m_min: float, uncut_mm: float, width_mm: float, rake_deg: float,
                 fc_n_per_mm: Optional[float] = None, ft_n_per_mm: Optional[float] = None,
                 chip_mm: Optional[float] = None, t_int_c: Optional[float] = None,
                 edge_radius_um: Optional[float] = None, flank_wear_mm: Optional[float] = None,
                 order: Optional[float] = None) -> None: ...
    @property
    def test(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...

class IdentifyResult:
    """Result of the Eq 15 identification."""
    @property
    def jc(self) -> JcParams: ...
    @property
    def at_bounds(self) -> List[str]: ...
    @property
    def fields(self) -> Dict[str, npt.NDArray[np.float64]]:
        """Fig 4 fields: x_mm, gamma, gamma_dot_per_s, eps, eps_dot_per_s, tau_mpa, sigma_eff_mpa, temperature_c."""
    @property
    def spread(self) -> Optional[Dict[str, Any]]: ...
    @property
    def json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...

def read_tests(path: _Path) -> List[CuttingTest]: ...
def identify(material: Material, test: CuttingTest, model: str = "enhanced", starts: int = 32, seed: int = 1,
             preset: str = "converged", h_mm: Optional[float] = None, points: Optional[int] = None,
             r: Optional[float] = None,
             rho_cp_original: Optional[float] = None, tolerance_c: float = 1e-6, max_iterations: int = 50,
             bootstrap: int = 0, force_uncertainty: Optional[float] = None, chip_uncertainty: Optional[float] = None,
             bootstrap_starts: int = 2, field_points: int = 201, noise_only: bool = False,
             every_start: bool = False) -> IdentifyResult:
    """JC from one test: DPZD zone (paper Sec 3, Eqs 1-12; Sec 3.5 fixed point), Eq 15 fit."""
def joint(material: Material, tests: List[CuttingTest], starts: int = 4, seed: int = 1,
          use_chip_thickness: bool = True, sharp: bool = False, material_class: Optional[str] = None,
          fix: Optional[Dict[str, float]] = None, work_temperature_c: Optional[float] = None) -> Dict[str, Any]:
    """JC fitted jointly to every measured test through the extended Oxley model (Oxley 1989, Lalwani
    et al. 2009); `jc` is a JcParams only when the verdict says the data determine the set."""
def predict(material: Material, jc: JcParams, tests: List[CuttingTest], work_temperature_c: Optional[float] = None,
            lalwani_ranges: bool = False, eta: Optional[float] = None, psi: Optional[float] = None,
            sharp: bool = False) -> Dict[str, Any]: ...
def _predict_many(material: Material, jc: JcParams, speed_m_min: npt.NDArray[np.float64],
                  uncut_mm: npt.NDArray[np.float64], width_mm: npt.NDArray[np.float64],
                  rake_deg: npt.NDArray[np.float64], edge_radius_um: Optional[npt.NDArray[np.float64]] = None,
                  flank_wear_mm: Optional[npt.NDArray[np.float64]] = None, work_temperature_c: Optional[float] = None,
                  lalwani_ranges: bool = False) -> Tuple[Dict[str, npt.NDArray[np.float64]], npt.NDArray[np.bool_], List[Optional[str]], float]: ...
def render(material: Material, jc: JcParams, format: str, units: str = "tonne-mm-s",
           t_from_c: Optional[float] = None, t_to_c: Optional[float] = None, t_step_c: float = 100.0,
           strain_rate_per_s: float = 1e4, heat_fraction: float = 0.9, source_test: Optional[str] = None,
           model_variant: str = "as identified in the JC file", contact_temperature_c: Optional[float] = None,
           cutting_speed_m_per_min: Optional[float] = None) -> Dict[str, str]: ...
def export(material: Material, jc: JcParams, format: str = "all", out: _Path = ".", units: str = "tonne-mm-s",
           t_from_c: Optional[float] = None, t_to_c: Optional[float] = None, t_step_c: float = 100.0,
           strain_rate_per_s: float = 1e4, heat_fraction: float = 0.9, source_test: Optional[str] = None,
           model_variant: str = "as identified in the JC file", contact_temperature_c: Optional[float] = None,
           cutting_speed_m_per_min: Optional[float] = None) -> List[str]: ...
def diagnose(recordings: _Path, simulation: Optional[_Path] = None, material: Optional[_Path] = None,
             jc: Optional[_Path] = None, free_jc: bool = False, model: Optional[str] = None) -> Dict[str, Any]: ...
