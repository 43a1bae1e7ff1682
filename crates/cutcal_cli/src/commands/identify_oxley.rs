//! `cutcal identify --method oxley`: Johnson-Cook parameters fitted jointly to the measured forces
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
use std::path::PathBuf;

use anyhow::{Context, Result};
use cutcal_ident::joint::{identify_oxley, JointOptions, JointVerdict, OxleyIdentification, Quantity};
use cutcal_ident::literature::MaterialClass;
use cutcal_ident::{JcConstants, MultistartOptions};
use cutcal_model::oxley::Physics;

use crate::commands::identify::jc_bounds;
use crate::commands::predict::oxley_options;
use cutcal_io::material_file::load_material;
use cutcal_io::tests_csv::{load_tests_measuring, MeasuredColumn};

/// Arguments of `cutcal identify --method oxley` (the dispatcher passes them through).
#[derive(Debug, Clone, clap::Args)]
pub struct IdentifyOxleyArgs {
    /// Material file (TOML) with thermal data and `[bounds]`.
    #[arg(long)]
    pub material: PathBuf,
    /// Tests (CSV) with measured forces.
    #[arg(long)]
    pub tests: PathBuf,
    /// Multistart starts.
    #[arg(long, default_value_t = 8)]
    pub starts: usize,
    /// Multistart seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Work-material temperature, degC (default: the material's room temperature).
    #[arg(long)]
    pub work_temperature_c: Option<f64>,
    /// Do not fit the measured chip thickness.
    #[arg(long)]
    pub no_chip: bool,
    /// Ignore the tests' edge radius and flank wear in the forward model (sharp, unworn tool).
    #[arg(long)]
    pub sharp: bool,
    /// Material class for the literature box of n, C and m: steel, titanium, aluminium, or none
    /// (the material's own bounds only). Default: from the room-temperature density.
    #[arg(long)]
    pub class: Option<String>,
    /// Fix a parameter at a value, NAME=VALUE with NAME one of a_mpa, b_mpa, n, c, m (repeatable),
    /// for example the n, C and m of a published set when the data cannot determine all five.
    #[arg(long = "fix", value_name = "NAME=VALUE")]
    pub fix: Vec<String>,
}

/// Applies `--fix NAME=VALUE` arguments to `bounds`.
pub fn apply_fixes(bounds: &mut cutcal_ident::JcBounds, fixes: &[(String, f64)]) -> Result<()> {
    for (name, value) in fixes {
        cutcal_ident::joint::fix_parameter(bounds, name, *value).with_context(|| format!("--fix {name}={value}"))?;
    }
    Ok(())
}

fn parse_fix(s: &str) -> Result<(String, f64)> {
    let (name, value) = s.split_once('=').ok_or_else(|| anyhow::anyhow!("--fix {s:?}: expected NAME=VALUE"))?;
    let v: f64 = value.trim().parse().map_err(|_| anyhow::anyhow!("--fix {s:?}: {value:?} is not a number"))?;
    Ok((name.trim().to_string(), v))
}

/// The material class: `arg` (`steel`, `titanium`, `aluminium`, `none`) or, without it, the class
/// of the room-temperature density.
pub fn material_class(arg: Option<&str>, material: &cutcal_model::Material) -> Result<Option<MaterialClass>> {
    match arg {
        Some(s) if s.trim().eq_ignore_ascii_case("none") => Ok(None),
        Some(s) => MaterialClass::parse(s)
            .map(Some)
            .ok_or_else(|| anyhow::anyhow!("--class {s:?}: expected steel, titanium, aluminium or none")),
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

/// Runs the joint identification.
pub fn run(args: &IdentifyOxleyArgs) -> Result<()> {
    let mf = load_material(&args.material)?;
    let tests = load_tests_measuring(
        &args.tests,
        &[MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce],
        "the joint Oxley identification needs measured Fc and Ft (tc where measured)",
    )?;
    let mut bounds = jc_bounds(&mf)?;
    let fixes = args.fix.iter().map(|f| parse_fix(f)).collect::<Result<Vec<_>>>()?;
    apply_fixes(&mut bounds, &fixes)?;
    let oxley = oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)
        .with_context(|| format!("Oxley options for {}", args.material.display()))?;
    let options = JointOptions {
        oxley,
        physics: Physics::baseline(),
        work_temperature_c: args.work_temperature_c.unwrap_or(mf.material.room_c),
        use_chip_thickness: !args.no_chip,
        tool_condition: !args.sharp,
    };
    let constants = JcConstants { eps0_per_s: 1.0, tm_c: mf.material.melting_c, tr_c: mf.material.room_c };
    let id = identify_oxley(
        &mf.material,
        &tests,
        &bounds,
        material_class(args.class.as_deref(), &mf.material)?,
        constants,
        &options,
        &MultistartOptions::new(args.starts, args.seed),
    )
    .with_context(|| format!("joint Oxley identification from {}", args.tests.display()))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&id)?);
    } else {
        print!("{}", table(&mf.material.name, &id));
    }
    Ok(())
}
