//! The bootstrap of a DPZD identification (`cutcal identify --bootstrap N`): uncertainty of the identified JC parameters from the stated
//! uncertainty of the measured Fc, Ft and tc (library: [`cutcal_ident::bootstrap`]).
//!
//! The uncertainty of each quantity is, in this order: the command-line value; the test row's own
//! uncertainty column (`fc_sd_n_per_mm`, `ft_sd_n_per_mm`, `chip_sd_mm`, e.g. written by
//! `cutcal recordings`, or the spread of repeats), relative to the measured value, the larger of
//! the two force channels since the resampling uses one force uncertainty; otherwise 3 % (forces)
//! and 5 % (chip). The report says which source was used.
//!
//! Each sample perturbs the measurements, rebuilds the test (validated like the CSV reader does),
//! re-solves the DPZD zone and re-runs the multistart identification with `--bootstrap-starts`
//! starts (fewer than the nominal fit's: the nominal fit shows how many starts reach the best
//! minimum). Samples run in parallel on rayon's pool (`RAYON_NUM_THREADS` sets its size); the
//! report does not depend on the thread count.

use std::fmt::Write as _;
use std::sync::atomic::{AtomicUsize, Ordering};

use cutcal_ident::bootstrap::{
    bootstrap, BootstrapOptions, BootstrapReport, Measurement, RelativeUncertainty, Sample, UnstatedChoices,
};
use cutcal_ident::monte_carlo::{SampleObjective, WarmSampleIdentifier};
use cutcal_ident::{IdentError, JcConstants, MultistartOptions};
use cutcal_model::CuttingTest;
use serde::Serialize;

use cutcal_io::material_file::MaterialFile;

use crate::dpzd::{jc_bounds, DpzdIdentifyReport, DpzdSettings, Preset};
use crate::error::{Context, Result};

/// Bootstrap options of an identification (the CLI's `--bootstrap*` flags, Python's keywords).
#[derive(Debug, Clone, PartialEq)]
pub struct BootstrapRequest {
    /// Resample the measured Fc, Ft and tc this many times (0: off).
    pub bootstrap: usize,
    /// Relative standard uncertainty of the measured forces (`None`: the row's sd, else 3 %).
    pub force_uncertainty: Option<f64>,
    /// Relative standard uncertainty of the measured chip thickness (`None`: the row's sd, else 5 %).
    pub chip_uncertainty: Option<f64>,
    /// Multistart starts per bootstrap sample.
    pub bootstrap_starts: usize,
    /// Vary only the measurements, not the unstated choices h and r.
    pub noise_only: bool,
    /// Range of the factor on h varied with the measurements (log-uniform): LOW HIGH.
    pub h_factor_range: Vec<f64>,
    /// Half-width of the uniform range of r varied with the measurements.
    pub r_half_width: f64,
}

impl Default for BootstrapRequest {
    fn default() -> Self {
        Self {
            bootstrap: 0,
            force_uncertainty: None,
            chip_uncertainty: None,
            bootstrap_starts: 2,
            noise_only: false,
            h_factor_range: vec![0.5, 2.0],
            r_half_width: 1.0,
        }
    }
}

impl BootstrapRequest {
    /// The unstated choices to vary (`None` with `--noise-only`).
    pub fn choices(&self) -> Result<Option<UnstatedChoices>> {
        if self.noise_only {
            return Ok(None);
        }
        let [lo, hi] = match self.h_factor_range.as_slice() {
            [lo, hi] => [*lo, *hi],
            other => crate::bail!("--h-factor-range takes LOW HIGH, got {other:?}"),
        };
        Ok(Some(UnstatedChoices::new([lo, hi], self.r_half_width).context("--h-factor-range / --r-half-width")?))
    }
}

/// Runs the bootstrap when `--bootstrap N` asks for it (`None` when N = 0).
///
/// The master seed is the identification's `--seed`.
///
/// Returns an error if the options are out of range, the test lacks a measurement, or fewer than
/// two samples can be identified.
pub fn run_bootstrap(
    args: &BootstrapRequest,
    mf: &MaterialFile,
    test: &CuttingTest,
    settings: &DpzdSettings,
    nominal_fit: &crate::dpzd::DpzdOutcome,
) -> Result<Option<BootstrapOutcome>> {
    if args.bootstrap == 0 {
        return Ok(None);
    }
    let (force, chip, source) = uncertainty_of(args, test);
    let uncertainty = RelativeUncertainty::new(force, chip).context("--force-uncertainty / --chip-uncertainty")?;
    if !(1..=1000).contains(&args.bootstrap_starts) {
        crate::bail!("--bootstrap-starts must be in 1..=1000, got {}", args.bootstrap_starts);
    }
    let missing = |what: &str| format!("test {}: --bootstrap needs the measured {what}", test.id);
    let nominal = Measurement {
        cutting_force_n_per_m: test.measured.cutting_force_n_per_m.with_context(|| missing("cutting force"))?,
        feed_force_n_per_m: test.measured.feed_force_n_per_m.with_context(|| missing("feed force"))?,
        chip_thickness_m: test.measured.chip_thickness_m.with_context(|| missing("chip thickness"))?,
    };
    let choices = args.choices()?;
    let bounds = jc_bounds(mf)?;
    let constants = JcConstants { eps0_per_s: 1.0, tm_c: mf.material.melting_c, tr_c: mf.material.room_c };
    // Each sample is identified warm from the nominal fit (its first start is the nominal
    // solution; `cutcal_ident::monte_carlo`), with the same objective and law as the nominal
    // identification (issue 11 presets).
    let multistart = MultistartOptions { starts: args.bootstrap_starts, ..settings.multistart };
    let objective = match settings.preset {
        Preset::Paper => {
            SampleObjective::Uniform { points: settings.points, rate_term: cutcal_model::RateTerm::Unclamped }
        }
        Preset::Converged => SampleObjective::Converged(cutcal_ident::ConvergedOptions::monte_carlo()),
    };
    let warm = WarmSampleIdentifier::new(
        &mf.material,
        test,
        settings.config()?,
        bounds,
        constants,
        objective,
        multistart,
        &nominal_fit.zone,
        &nominal_fit.identification,
    )?;
    // Samples that end at a bound of the box, counted as they finish (the count does not depend
    // on the order, so the report stays identical for any thread count).
    let boxes = [bounds.a_mpa, bounds.b_mpa, bounds.n, bounds.c, bounds.m];
    let counts: [[AtomicUsize; 2]; 5] = Default::default();
    let identify = |s: &Sample| -> Result<cutcal_model::JcParams, IdentError> {
        let jc = warm.identify(s)?;
        let v = [jc.a_pa / 1e6, jc.b_pa / 1e6, jc.n, jc.c, jc.m];
        for ((x, [lo, hi]), count) in v.iter().zip(boxes).zip(&counts) {
            let tol = 1e-9 * (hi - lo).abs().max(f64::MIN_POSITIVE);
            if *x <= lo + tol {
                count[0].fetch_add(1, Ordering::Relaxed);
            } else if *x >= hi - tol {
                count[1].fetch_add(1, Ordering::Relaxed);
            }
        }
        Ok(jc)
    };
    let options = BootstrapOptions { samples: args.bootstrap, seed: settings.multistart.seed, uncertainty, choices };
    let report = bootstrap(&nominal, &options, identify)
        .with_context(|| format!("bootstrap of test {} ({} samples)", test.id, args.bootstrap))?;
    let at_bounds = cutcal_ident::dpzd_fit::JC_NAMES
        .iter()
        .zip(boxes)
        .zip(&counts)
        .map(|((name, bounds), c)| SamplesAtBound {
            name: (*name).to_string(),
            bounds,
            at_lower: c[0].load(Ordering::Relaxed),
            at_upper: c[1].load(Ordering::Relaxed),
        })
        .collect();
    Ok(Some(BootstrapOutcome { report, source, at_bounds }))
}

/// A bootstrap report and where its uncertainties came from.
#[derive(Debug, Clone, Serialize)]
pub struct BootstrapOutcome {
    /// The library's report.
    #[serde(flatten)]
    pub report: BootstrapReport,
    /// Source of the force and chip uncertainties, e.g. `forces: the row's sd columns (...)`.
    pub source: String,
    /// For A, B, n, C and m: how many successful samples ended at each bound of the box (the
    /// spread is conditional on those bounds: the fit presses against them).
    pub at_bounds: Vec<SamplesAtBound>,
}

/// The successful Monte-Carlo samples that ended at a bound of one parameter's box.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SamplesAtBound {
    /// Parameter name (`a_mpa`, `b_mpa`, `n`, `c`, `m`).
    pub name: String,
    /// The box `[lower, upper]` of the identification.
    pub bounds: [f64; 2],
    /// Samples at the lower bound (within 1e-9 of the box width).
    pub at_lower: usize,
    /// Samples at the upper bound.
    pub at_upper: usize,
}

/// The force and chip uncertainties: the flag, else the row's sd columns, else 3 % / 5 %.
fn uncertainty_of(args: &BootstrapRequest, test: &CuttingTest) -> (f64, f64, String) {
    let m = test.measured;
    let rel = |sd: Option<f64>, v: Option<f64>| match (sd, v) {
        (Some(s), Some(v)) if v > 0.0 && s.is_finite() => Some(s / v),
        _ => None,
    };
    let fc = rel(m.sd.cutting_force_n_per_m, m.cutting_force_n_per_m);
    let ft = rel(m.sd.feed_force_n_per_m, m.feed_force_n_per_m);
    let (force, fsrc) = match (args.force_uncertainty, fc, ft) {
        (Some(f), _, _) => (f, "forces: --force-uncertainty".to_string()),
        (None, Some(a), Some(b)) => (
            a.max(b),
            format!("forces: the row's sd columns (Fc {:.2} %, Ft {:.2} %; the larger)", 100.0 * a, 100.0 * b),
        ),
        (None, Some(a), None) | (None, None, Some(a)) => {
            (a, format!("forces: the row's sd column ({:.2} %)", 100.0 * a))
        }
        (None, None, None) => (0.03, "forces: default 3 % (the row states no sd)".to_string()),
    };
    let (chip, csrc) = match (args.chip_uncertainty, rel(m.sd.chip_thickness_m, m.chip_thickness_m)) {
        (Some(c), _) => (c, "chip: --chip-uncertainty".to_string()),
        (None, Some(c)) => (c, format!("chip: the row's sd column ({:.2} %)", 100.0 * c)),
        (None, None) => (0.05, "chip: default 5 % (the row states no sd)".to_string()),
    };
    (force, chip, format!("{fsrc}; {csrc}"))
}

/// The identification report with a `bootstrap` key appended (field order kept).
#[derive(Serialize)]
struct WithBootstrap<'a> {
    #[serde(flatten)]
    report: &'a DpzdIdentifyReport,
    bootstrap: &'a BootstrapOutcome,
}

/// Pretty JSON of the report, with a `bootstrap` key when there is one (byte-identical to the
/// report alone otherwise).
pub fn report_json(report: &DpzdIdentifyReport, boot: Option<&BootstrapOutcome>) -> Result<String> {
    Ok(match boot {
        None => serde_json::to_string_pretty(report)?,
        Some(b) => serde_json::to_string_pretty(&WithBootstrap { report, bootstrap: b })?,
    })
}

/// Human-readable table of a bootstrap report.
#[must_use]
pub fn render_bootstrap(b: &BootstrapOutcome) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "  Monte-Carlo propagation (--bootstrap; no data are resampled): {} samples ({} failed), Fc/Ft +-{:.1} %, tc +-{:.1} % (1 sigma; {}), seed {}",
        b.report.samples,
        b.report.failed,
        100.0 * b.report.uncertainty.force,
        100.0 * b.report.uncertainty.chip_thickness,
        b.source,
        b.report.seed
    );
    match &b.report.choices {
        Some(c) => {
            let _ = writeln!(
                s,
                "  with the unstated choices: h x [{}, {}] (log-uniform), r +- {} (uniform)",
                c.h_factor[0], c.h_factor[1], c.r_half_width
            );
        }
        None => {
            let _ = writeln!(s, "  measurement noise only (--noise-only): h and r fixed");
        }
    }
    let at_bounds = &b.at_bounds;
    let b = &b.report;
    let _ = writeln!(s, "  parameter        mean         std        2.5 %       97.5 %");
    for p in &b.parameters {
        let _ = writeln!(s, "  {:<8} {:>11.5} {:>11.5} {:>12.5} {:>12.5}", p.name, p.mean, p.std, p.q025, p.q975);
    }
    let _ = writeln!(s, "  bootstrap correlation (- where a parameter does not vary):");
    for row in &b.correlation {
        let cells: Vec<String> =
            row.iter().map(|c| c.map_or_else(|| format!("{:>7}", "-"), |v| format!("{v:>7.3}"))).collect();
        let _ = writeln!(s, "    {}", cells.join(" "));
    }
    for a in at_bounds.iter().filter(|a| a.at_lower + a.at_upper > 0) {
        let mut parts = Vec::new();
        if a.at_lower > 0 {
            parts.push(format!("at its lower bound {} in {} of {} samples", a.bounds[0], a.at_lower, b.succeeded));
        }
        if a.at_upper > 0 {
            parts.push(format!("at its upper bound {} in {} of {} samples", a.bounds[1], a.at_upper, b.succeeded));
        }
        let _ = writeln!(
            s,
            "  {}: {} (the fit presses against the bound: the spread is conditional on it)",
            a.name,
            parts.join(", ")
        );
        if a.name == "n" && a.at_lower > 0 && a.bounds[0] == 0.0 {
            let _ = writeln!(
                s,
                "    n = 0 makes eps^n = 1: A and B are not separable in those samples (only A + B is), so their A and B spread reflects the optimiser, not the data"
            );
        }
    }
    if let Some(f) = &b.first_failure {
        let _ = writeln!(s, "  first failed sample: {f}");
    }
    s
}
