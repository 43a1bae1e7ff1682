//! `cutcal identify --method oxley`: Johnson-Cook parameters fitted jointly to the measured forces
//! (and chip thickness) of several tests through the extended Oxley model.
//!
//! Measurement columns of the tests CSV: `fc_n`, `ft_n` are totals in N over `width_mm`, or
//! `fc_n_per_mm`, `ft_n_per_mm` per unit width; `chip_mm` is the chip thickness (used unless
//! `--no-chip`); `t_int_c` is reported, not fitted. Residuals are relative errors, so each measured
//! quantity weighs the same whatever its size. Bounds come from the material's `[bounds]`;
//! eps0 = 1/s, Tm and Tr are the material's melting and room temperatures.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result};
use cutcal_ident::joint::{identify_oxley, JointOptions, OxleyIdentification, Quantity};
use cutcal_ident::{JcConstants, MultistartOptions};
use cutcal_model::oxley::Physics;

use crate::commands::identify::jc_bounds;
use crate::commands::predict::oxley_options;
use crate::input::material_file::load_material;
use crate::input::tests_csv::{load_tests_measuring, MeasuredColumn};

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

/// Runs the joint identification.
pub fn run(args: &IdentifyOxleyArgs) -> Result<()> {
    let mf = load_material(&args.material)?;
    let tests = load_tests_measuring(
        &args.tests,
        &[MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce],
        "the joint Oxley identification needs measured Fc and Ft (tc where measured)",
    )?;
    let bounds = jc_bounds(&mf)?;
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
