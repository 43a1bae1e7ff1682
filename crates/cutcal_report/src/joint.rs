//! The joint identification (`cutcal identify --method oxley`, a project's `[joint]`): Johnson-Cook parameters fitted jointly to the measured forces
//! (and chip thickness) of several tests through the extended Oxley model.
//!
//! Measurement columns of the tests CSV: `fc_n`, `ft_n` are totals in N over `width_mm`, or
//! `fc_n_per_mm`, `ft_n_per_mm` per unit width; `chip_mm` is the chip thickness (used unless
//! `--no-chip`); `t_int_c` is reported, not fitted. Residuals are relative errors, so each measured
//! quantity weighs the same whatever its size. Bounds come from the material's `[bounds]`, with
//! n, C and m kept inside the literature box of the material class (`cutcal_ident::literature`;
//! class from the density unless `--class` is given); eps0 = 1/s, Tm and Tr are the material's
//! melting and room temperatures. The verdict says whether the data determine the set
//! (`cutcal_ident::identifiability`).

use std::fmt::Write as _;
use std::path::Path;

use cutcal_ident::joint::{identify_oxley, JointOptions, JointVerdict, OxleyIdentification, Quantity};
use cutcal_ident::literature::MaterialClass;
use cutcal_ident::{JcConstants, MultistartOptions};
use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::tests_csv::{load_tests_measuring, MeasuredColumn};
use cutcal_model::oxley::{OxleyOptions, Physics};
use cutcal_model::CuttingTest;

use crate::dpzd::jc_bounds;
use crate::error::{Context, Error, Result};
use crate::predict::oxley_options;

/// Applies `--fix NAME=VALUE` arguments to `bounds`.
pub fn apply_fixes(bounds: &mut cutcal_ident::JcBounds, fixes: &[(String, f64)]) -> Result<()> {
    for (name, value) in fixes {
        cutcal_ident::joint::fix_parameter(bounds, name, *value).with_context(|| format!("--fix {name}={value}"))?;
    }
    Ok(())
}

/// Parses one `--fix NAME=VALUE` argument.
pub fn parse_fix(s: &str) -> Result<(String, f64)> {
    let (name, value) = s.split_once('=').ok_or_else(|| Error::invalid(format!("--fix {s:?}: expected NAME=VALUE")))?;
    let v: f64 = value.trim().parse().map_err(|_| Error::invalid(format!("--fix {s:?}: {value:?} is not a number")))?;
    Ok((name.trim().to_string(), v))
}

/// The material class: `arg` (`steel`, `titanium`, `aluminium`, `none`) or, without it, the class
/// of the room-temperature density.
pub fn material_class(arg: Option<&str>, material: &cutcal_model::Material) -> Result<Option<MaterialClass>> {
    match arg {
        Some(s) if s.trim().eq_ignore_ascii_case("none") => Ok(None),
        Some(s) => MaterialClass::parse(s)
            .map(Some)
            .ok_or_else(|| Error::invalid(format!("--class {s:?}: expected steel, titanium, aluminium or none"))),
        None => Ok(MaterialClass::from_density(material.thermal.density.value(material.room_c))),
    }
}

/// The readable report of a joint identification.
pub fn table(material: &str, id: &OxleyIdentification) -> String {
    let mut s = String::new();
    let j = &id.jc;
    let _ = writeln!(s, "joint Oxley identification for {material}");
    let _ = writeln!(
        s,
        "  A {:.1} MPa, B {:.1} MPa, n {:.4}, C {:.5}, m {:.4} (eps0 {} 1/s, Tm {} degC, Tr {} degC)",
        j.a_pa / 1e6,
        j.b_pa / 1e6,
        j.n,
        j.c,
        j.m,
        j.eps0_per_s,
        j.tm_c,
        j.tr_c
    );
    if let Some(se) = &id.statistics.std_errors {
        let pairs: Vec<String> = id.statistics.free.iter().zip(se).map(|(n, e)| format!("{n} +- {e:.4}")).collect();
        let _ = writeln!(s, "  standard errors: {}", pairs.join(", "));
    } else {
        let _ = writeln!(s, "  standard errors: not available (no degrees of freedom or singular J^T J)");
    }
    if !id.statistics.at_bounds.is_empty() {
        let _ = writeln!(s, "  at bounds: {}", id.statistics.at_bounds.join(", "));
    }
    let b = &id.bounds_used;
    let _ = writeln!(
        s,
        "  bounds used: n [{}, {}], C [{}, {}], m [{}, {}] ({})",
        b.n[0],
        b.n[1],
        b.c[0],
        b.c[1],
        b.m[0],
        b.m[1],
        match &id.literature {
            Some(l) => format!(
                "material bounds within the {} literature box of {} published sets",
                l.class.name(),
                l.sets.len()
            ),
            None => "the material's bounds; no literature box for this material".to_string(),
        }
    );
    if !id.outside_literature.is_empty() {
        let _ = writeln!(s, "  outside the literature box: {}", id.outside_literature.join(", "));
    }
    if let Some(a) = &id.identifiability {
        let _ = writeln!(
            s,
            "  identifiability: effective rank {} of {}, condition number {}, singular values {}",
            a.effective_rank,
            a.parameters.len(),
            a.condition_number.map_or_else(|| "infinite".to_string(), |c| format!("{c:.3e}")),
            a.singular_values.iter().map(|v| format!("{v:.3}")).collect::<Vec<_>>().join(" ")
        );
    }
    if id.unconverged_starts > 0 {
        let _ = writeln!(
            s,
            "  {} of {} starts stopped at the LM iteration cap and were excluded",
            id.unconverged_starts, id.starts
        );
    }
    let _ = writeln!(s, "  verdict: {}", verdict_line(&id.verdict));
    let _ = writeln!(
        s,
        "  rms relative error {:.2} %, starts {} (at best {}, failed {}), best start {}, {} LM iterations",
        100.0 * id.statistics.rms,
        id.starts,
        id.starts_at_best,
        id.failed_starts,
        id.best_start,
        id.iterations
    );
    for (o, r) in id.observations.iter().zip(&id.relative_errors) {
        let what = match o.quantity {
            Quantity::CuttingForce => "Fc",
            Quantity::FeedForce => "Ft",
            Quantity::ChipThickness => "tc",
        };
        let _ = writeln!(s, "  test #{:<3} {what}: error {:+.2} %", o.test + 1, 100.0 * r);
    }
    s
}

/// One line for a verdict.
#[must_use]
pub fn verdict_line(v: &JointVerdict) -> String {
    match v {
        JointVerdict::Determined => "determined: every free parameter direction is pinned down by the data".into(),
        JointVerdict::Undetermined { reason } => format!("REFUSED, not determined: {reason}"),
        JointVerdict::Misfit { reason } => format!("REFUSED, the model misfits the data: {reason}"),
        JointVerdict::NotConverged { reason } => format!("REFUSED, not converged: {reason}"),
    }
}

/// Options of a joint identification (the CLI's `identify --method oxley` flags, a project's
/// `[joint]` table, Python's keywords).
#[derive(Debug, Clone, PartialEq)]
pub struct JointRequest {
    /// Multistart starts (each ~1 s).
    pub starts: usize,
    /// Multistart seed.
    pub seed: u64,
    /// Work-material temperature, degC (`None`: the material's room temperature).
    pub work_temperature_c: Option<f64>,
    /// Fit the measured chip thickness where measured.
    pub use_chip_thickness: bool,
    /// Include the tests' edge radius and flank wear in the forward model.
    pub tool_condition: bool,
    /// Material class of the literature box (`steel`, `titanium`, `aluminium`, `none`; `None`:
    /// from the density).
    pub class: Option<String>,
    /// Parameters fixed at a value (a_mpa, b_mpa, n, c, m).
    pub fix: Vec<(String, f64)>,
}

impl Default for JointRequest {
    fn default() -> Self {
        Self {
            starts: 4,
            seed: 1,
            work_temperature_c: None,
            use_chip_thickness: true,
            tool_condition: true,
            class: None,
            fix: Vec::new(),
        }
    }
}

/// The joint identification of every measured test of `tests` (read from `tests_path`, named in
/// the error context) with the Oxley options `oxley`. `project` names the project in the context
/// of a bad `fix` or `class` (the project runner's `[joint]` table); `None` for the CLI's flags.
///
/// Returns an error if the material has no bounds, a fix or the class is refused, or the fit fails.
pub fn joint_fit(
    mf: &MaterialFile,
    tests: &[CuttingTest],
    tests_path: &Path,
    oxley: OxleyOptions,
    req: &JointRequest,
    project: Option<&str>,
) -> Result<OxleyIdentification> {
    let mut bounds = jc_bounds(mf)?;
    let fixed = apply_fixes(&mut bounds, &req.fix);
    let class = material_class(req.class.as_deref(), &mf.material);
    let (fixed, class) = match project {
        Some(p) => (
            fixed.with_context(|| format!("[joint] fix of project {p}")),
            class.with_context(|| format!("[joint] class of {p}")),
        ),
        None => (fixed, class),
    };
    fixed?;
    let class = class?;
    let options = JointOptions {
        oxley,
        physics: Physics::baseline(),
        work_temperature_c: req.work_temperature_c.unwrap_or(mf.material.room_c),
        use_chip_thickness: req.use_chip_thickness,
        tool_condition: req.tool_condition,
    };
    let constants = JcConstants { eps0_per_s: 1.0, tm_c: mf.material.melting_c, tr_c: mf.material.room_c };
    identify_oxley(
        &mf.material,
        tests,
        &bounds,
        class,
        constants,
        &options,
        &MultistartOptions::new(req.starts, req.seed),
    )
    .with_context(|| format!("joint Oxley identification from {}", tests_path.display()))
}

/// Reads the material and the tests (Fc and Ft measured; tc where measured) and runs the joint
/// identification: what `cutcal identify --method oxley` computes before it prints.
pub fn joint_files(material: &Path, tests: &Path, req: &JointRequest) -> Result<(MaterialFile, OxleyIdentification)> {
    let mf = load_material(material)?;
    let all = load_tests_measuring(
        tests,
        &[MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce],
        "the joint Oxley identification needs measured Fc and Ft (tc where measured)",
    )?;
    // The flags are checked before the options, as the command always did.
    let mut bounds = jc_bounds(&mf)?;
    apply_fixes(&mut bounds, &req.fix)?;
    let oxley = oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)
        .with_context(|| format!("Oxley options for {}", material.display()))?;
    let id = joint_fit(&mf, &all, tests, oxley, req, None)?;
    Ok((mf, id))
}
