//! cutcal_export: FE input cards from one identified material.
//!
//! From a workpiece [`Material`] (paper Table 3 laws), a [`JcParams`] set (paper Eq 16), an optional
//! tool material and the tool-chip [`Interface`] (paper Sec 5.1: Eq 17 shear friction or Coulomb,
//! heat transfer coefficient), [`render`] writes the cards of one [`Dialect`]:
//!
//! - **Abaqus**: native `*PLASTIC, HARDENING=JOHNSON COOK` + `*RATE DEPENDENT`, a tabular
//!   `*PLASTIC` variant for solvers without JC (run by CalculiX in the tests), and for Eq 17 a
//!   VFRIC user-subroutine source;
//! - **LS-DYNA**: `*MAT_JOHNSON_COOK` + EOS + thermal material with load curves, parts, and a
//!   thermal friction contact whose Eq 17 law is an FS=2 `*DEFINE_TABLE` of mu(P);
//! - **DEFORM-style**: a KEY-like material block (unverified: the KEY format is not public) and
//!   a readable sheet;
//! - **MatML 3.1** XML (quick-xml).
//!
//! [`render_cut2d`] writes a complete 2-D plane-strain LS-DYNA deck of one cutting test (mesh,
//! rigid conducting tool, contact, motion, output; [`deck2d`]).
//!
//! Data flow: [`ExportInput`] -> validation and sampling (`physics`) -> per-dialect template
//! context in the chosen [`UnitSystem`] -> handlebars templates (`templates/`, strict mode) with
//! Rust number helpers ([`numfmt`]) -> `Vec<`[`ExportFile`]`>`. No I/O: the CLI writes the files.
//!
//! The Eq 17 friction table (fe-cards.md §1.6):
//! ```text
//! tau_f = m0 (1 - exp(-beta P)) k          (paper Eq 17)
//! mu(P) = m0 k (1 - exp(-beta P)) / P,  mu(0) = m0 k beta,  cap tau <= m0 k
//! k(T)  = sigma_JC(2, 1e4 1/s, T) / sqrt(3) (local shear flow stress, paper Eqs 14, 16)
//! ```
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]

mod abaqus;
pub mod deck2d;
pub mod deck2d_mesh;
mod deform;
mod error;
mod lsdyna;
mod matml;
pub mod numfmt;
pub mod physics;
mod templates;
pub mod units;

use cutcal_model::{Interface, JcParams, Material};
use serde::Serialize;

pub use deck2d::render_cut2d;
pub use error::ExportError;
pub use units::UnitSystem;

/// Plastic strains of tabular flow-stress cards (Abaqus tabular `*PLASTIC`, DEFORM-style FSTRES):
/// from 0 to 5, covering primary and secondary shear zones (fe-cards.md §3: ε 0–5), with
/// 0.001-0.005 for the steep start of the JC hardening term. Linear interpolation between them stays
/// within 1 % of the JC law for ε in [0.001, 5] for the fixture JC sets (unit test
/// `tabular_strains_interpolate_jc_within_one_percent`); below 0.001 the infinite slope of B ε^n at
/// 0 makes any table miss.
pub const STANDARD_PLASTIC_STRAINS: [f64; 14] =
    [0.0, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 3.0, 5.0];

/// Strain rates (1/s) of the DEFORM-style FSTRES table: 1 to 1e6 1/s (fe-cards.md §3).
pub const STANDARD_FLOW_STRAIN_RATES_PER_S: [f64; 7] = [1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6];

/// Contact pressures (MPa) of the Eq 17 mu(P) table: 0, then 1 to 3000 MPa log-spaced, 12 points
/// per decade (ratio 10^(1/12), 5 significant digits). With beta = 0.0045/MPa (steel, paper Sec
/// 5.1) `1 - exp(-beta P)` reaches 0.9999986 at 3000 MPa. Linear interpolation of mu = tau/P
/// between points of ratio r overstates tau by at most (2 + r + 1/r)/4 - 1 = 0.92 % (where mu ~ 1/P),
/// so the table stays within 1 % of Eq 17 (test `interpolated_eq17_is_within_one_percent`).
pub const STANDARD_CONTACT_PRESSURES_MPA: [f64; 44] = [
    0.0, 1.0, 1.2115, 1.4678, 1.7783, 2.1544, 2.6102, 3.1623, 3.8312, 4.6416, 5.6234, 6.8129, 8.254, 10.0, 12.115,
    14.678, 17.783, 21.544, 26.102, 31.623, 38.312, 46.416, 56.234, 68.129, 82.54, 100.0, 121.15, 146.78, 177.83,
    215.44, 261.02, 316.23, 383.12, 464.16, 562.34, 681.29, 825.4, 1000.0, 1211.5, 1467.8, 1778.3, 2154.4, 2610.2,
    3000.0,
];

/// The FE dialects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Dialect {
    /// Abaqus keywords (native JC, tabular variant, VFRIC source).
    Abaqus,
    /// LS-DYNA keyword deck.
    LsDyna,
    /// DEFORM-style KEY block and sheet.
    Deform,
    /// MatML 3.1 XML.
    MatMl,
}

impl Dialect {
    /// Every dialect, in output order.
    pub const ALL: [Self; 4] = [Self::Abaqus, Self::LsDyna, Self::Deform, Self::MatMl];

    /// Lower-case name (`abaqus`, `lsdyna`, `deform`, `matml`), used in snapshot names.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Abaqus => "abaqus",
            Self::LsDyna => "lsdyna",
            Self::Deform => "deform",
            Self::MatMl => "matml",
        }
    }
}

/// Where the numbers come from; printed in every file header.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    /// cutcal version (e.g. `env!("CARGO_PKG_VERSION")` of the CLI).
    pub cutcal_version: String,
    /// The cutting test(s) the JC set was identified from (e.g. `C38 test 3`).
    pub source_test: String,
    /// The model variant (e.g. `enhanced DPZD`, `paper Table 5`).
    pub model_variant: String,
}

/// Temperature sampling of the Table 3 polynomials (each material is sampled over the overlap
/// of this range with its own validity range; the upper bound is always included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemperatureGrid {
    /// Lowest temperature, degC.
    pub from_c: f64,
    /// Highest temperature, degC.
    pub to_c: f64,
    /// Step, degC.
    pub step_c: f64,
}

/// Export options. No `Default`: every physical choice is made by the caller (style.md §15).
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// Unit system of the Abaqus and LS-DYNA cards (DEFORM-style is always SI-mm-degC, MatML SI).
    pub units: UnitSystem,
    /// Temperatures of property and flow-stress tables.
    pub temperatures: TemperatureGrid,
    /// Plastic strains of tabular flow stress (first must be 0), e.g. [`STANDARD_PLASTIC_STRAINS`].
    pub plastic_strains: Vec<f64>,
    /// Strain rate (1/s) of the tabular Abaqus `*PLASTIC` variant.
    pub tabular_strain_rate_per_s: f64,
    /// Strain rates (1/s) of the DEFORM-style FSTRES table.
    pub flow_strain_rates_per_s: Vec<f64>,
    /// Contact pressures (Pa) of the Eq 17 mu(P) table.
    pub contact_pressures_pa: Vec<f64>,
    /// Fraction of plastic work converted to heat (Taylor-Quinney; not given in the paper).
    pub inelastic_heat_fraction: f64,
    /// Tool-chip contact temperature at which the LS-DYNA FS = 2 friction table evaluates the
    /// Eq 17 shear strength k(T): LS-DYNA's documented FS = 2 table is mu(P, v_rel) with no
    /// temperature (docs/fe-cards.md). `None`: [`physics::default_contact_temperature_c`], stated
    /// as a default in the deck.
    pub contact_temperature: Option<ContactTemperature>,
    /// Cutting speed (m/s) of the condition the deck is run for: the LS-DYNA termination time is
    /// the paper's 8 mm cut over it (paper Sec 5.1). `None`: no `*CONTROL_TERMINATION` (stated).
    pub cutting_speed_m_per_s: Option<f64>,
}

/// A tool-chip contact temperature and where it comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactTemperature {
    /// Temperature, degC; must lie in [Tr, Tm) of the JC set.
    pub temp_c: f64,
    /// Its source, printed in the deck header (1-60 printable ASCII characters without commas),
    /// e.g. `"measured interface temperature of test 1"`.
    pub source: String,
}

/// Everything one export needs.
#[derive(Debug, Clone, Copy)]
pub struct ExportInput<'a> {
    /// The workpiece material (Table 3 laws, SI, degC).
    pub workpiece: &'a Material,
    /// The JC set (Pa, degC).
    pub jc: &'a JcParams,
    /// The tool material, when known (rendered as an elastic/thermal material).
    pub tool: Option<&'a Material>,
    /// The tool-chip interface (paper Sec 5.1).
    pub interface: &'a Interface,
    /// Provenance for headers.
    pub provenance: &'a Provenance,
    /// Options.
    pub options: &'a ExportOptions,
}

/// One rendered file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExportFile {
    /// File name (no directory), e.g. `c38_lsdyna.k`.
    pub name: String,
    /// Contents.
    pub contents: String,
}

/// Renders every file of `dialect`.
///
/// Returns an error if the input fails validation, an option is out of range, a derived number
/// is NaN or infinite, a name cannot be written, or a dialect lacks data it needs (e.g. elastic
/// constants for Abaqus and LS-DYNA). Nothing partial is returned.
pub fn render(dialect: Dialect, input: &ExportInput<'_>) -> Result<Vec<ExportFile>, ExportError> {
    let prepared = physics::prepare(input)?;
    let hb = templates::registry()?;
    match dialect {
        Dialect::Abaqus => abaqus::render(&hb, &prepared, input),
        Dialect::LsDyna => lsdyna::render(&hb, &prepared, input),
        Dialect::Deform => deform::render(&hb, &prepared, input),
        Dialect::MatMl => matml::render(&prepared, input),
    }
}

/// Renders every dialect (see [`render`]).
///
/// Returns the first error of any dialect; nothing partial is returned.
pub fn render_all(input: &ExportInput<'_>) -> Result<Vec<ExportFile>, ExportError> {
    let mut out = Vec::new();
    for d in Dialect::ALL {
        out.extend(render(d, input)?);
    }
    Ok(out)
}

/// Common header fields of every template context.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct HeaderCtx {
    pub version: String,
    pub source_test: String,
    pub model_variant: String,
    pub units: String,
    /// One line per JC parameter outside the literature box of the workpiece's class.
    pub warnings: Vec<String>,
}

impl HeaderCtx {
    pub(crate) fn new(input: &ExportInput<'_>, units: &str) -> Self {
        Self {
            version: input.provenance.cutcal_version.clone(),
            source_test: input.provenance.source_test.clone(),
            model_variant: input.provenance.model_variant.clone(),
            units: units.to_string(),
            warnings: literature_warnings(input),
        }
    }
}

/// The JC parameters outside the literature box of the workpiece's material class
/// (`cutcal_ident::literature`; class from the room-temperature density), one line each, for every
/// file header: a set outside its stated physical bounds is never exported silently.
#[must_use]
pub fn literature_warnings(input: &ExportInput<'_>) -> Vec<String> {
    use cutcal_ident::literature::{LiteratureBox, MaterialClass};
    let m = input.workpiece;
    let Some(class) = MaterialClass::from_density(m.thermal.density.value(m.room_c)) else {
        return Vec::new();
    };
    let lit = LiteratureBox::of(class);
    lit.outside(input.jc.n, input.jc.c, input.jc.m)
        .into_iter()
        .map(|o| format!("JC {o}: outside the {} literature box of {} published sets", class.name(), lit.sets.len()))
        .collect()
}
