//! The diagnosis report: the JSON keys of issue 6 plus supporting detail, and a plain-text rendering.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

/// The overall finding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// A library mechanism is missing and passed every acceptance rule.
    MissingPhysics,
    /// No significant mismatch.
    None,
    /// Several mechanisms explain the mismatch equally well, or the design cannot validate one.
    Ambiguous,
    /// A significant mismatch that no library mechanism explains.
    Unexplained,
}

impl Verdict {
    /// The snake_case spelling.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::MissingPhysics => "missing_physics",
            Verdict::None => "none",
            Verdict::Ambiguous => "ambiguous",
            Verdict::Unexplained => "unexplained",
        }
    }
}

/// Where the model and the recordings differ, per output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mismatch {
    /// `fc`, `ft` or `tc`.
    pub output: String,
    /// Mean of (measured - model)/model, %.
    pub bias_pct: f64,
    /// The strongest trend of the relative residual against a covariate, or `none`.
    pub trend: String,
    /// Smallest (Holm-adjusted) p-value of the bias and trend tests.
    pub p_value: f64,
    /// Tests whose residual exceeds two noise standard deviations.
    pub tests: Vec<String>,
}

/// A parameter estimate with its 95 % interval.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamValue {
    /// Estimate.
    pub value: f64,
    /// Unit.
    pub unit: String,
    /// Lower end of the 95 % interval (clipped to the bounds); `None` when not available.
    pub ci_low: Option<f64>,
    /// Upper end of the 95 % interval (clipped to the bounds); `None` when not available.
    pub ci_high: Option<f64>,
    /// Why the interval is not available (empty when it is).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub ci_note: String,
}

/// One refitted mechanism.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismResult {
    /// Library id.
    pub id: String,
    /// Whether it passed every acceptance rule.
    pub accepted: bool,
    /// Fitted parameters.
    pub params: BTreeMap<String, ParamValue>,
    /// AICc(with mechanism) - AICc(baseline); negative favours the mechanism. `None` when AICc is
    /// undefined (n <= k + 1 or a perfect fit).
    pub delta_aicc: Option<f64>,
    /// F-test p-value of the joint refit against the baseline (one-sided where the parameter is);
    /// `None` when there are too few numbers for the test.
    pub p_value: Option<f64>,
    /// Leave-one-condition-out RMS (%, all outputs) of the baseline, when the design allows it.
    pub heldout_rms_before: Option<f64>,
    /// Leave-one-condition-out RMS (%, all outputs) with the mechanism.
    pub heldout_rms_after: Option<f64>,
    /// Share of the baseline misfit the mechanism removes in-sample.
    pub explained_fraction: f64,
    /// Share of the mechanism's signature the baseline parameters can produce within their stated
    /// priors (linearised at the screen's probe; `crate::detect::BaselineInfo::absorbed_share`): near 1, the
    /// nuisance alone could account for this mechanism's effect.
    pub absorption: f64,
    /// Score-test p-value from the screen; `None` when there are too few numbers for the test.
    pub screen_p_value: Option<f64>,
    /// Why it was or was not accepted.
    pub reason: String,
    /// The smallest move of each strength parameter this design would detect (`crate::detect`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub detection_limits: Vec<DetectionLimit>,
}

/// The smallest move of one strength parameter from its off value that the significance test would
/// detect with [`crate::detect::POWER`] power at the round's level, alone, with the baseline free
/// (Baarda 1968's minimal detectable bias, linearised at the screen's probe). A necessary condition
/// for a claim, not a sufficient one: the held-out, ambiguity and instrument checks come after.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DetectionLimit {
    /// Parameter name.
    pub param: String,
    /// Unit.
    pub unit: String,
    /// Values at or below this are detected; `None` with the reason in `note`.
    pub below: Option<f64>,
    /// Values at or above this are detected; `None` with the reason in `note`.
    pub above: Option<f64>,
    /// The limit in the parameter's typical magnitudes (above 1: a typical-size effect goes unseen).
    pub typical_units: Option<f64>,
    /// Why a side is not available (empty when both are).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
}

/// RMS of the relative error, % per output and over all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutputRms {
    /// Cutting force.
    pub fc: Option<f64>,
    /// Feed force.
    pub ft: Option<f64>,
    /// Chip thickness.
    pub tc: Option<f64>,
    /// Interface temperature rise, where measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_int: Option<f64>,
    /// Fc, Ft and tc pooled.
    pub all: f64,
}

/// Fit quality of one model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitStats {
    /// In-sample.
    pub in_sample: OutputRms,
    /// Leave-one-condition-out (nested for the "after" model), when there are >= 3 conditions.
    pub loco: Option<OutputRms>,
}

/// Before (baseline) and after (selected mechanisms).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitSummary {
    /// Baseline.
    pub before: FitStats,
    /// With the selected mechanisms (equal to before when none is selected).
    pub after: FitStats,
}

/// A named parameter value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NamedValue {
    /// Name.
    pub name: String,
    /// Value.
    pub value: f64,
}

/// Residual of one observation before and after, % (measured - model)/model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResidualRow {
    /// Test id.
    pub test: String,
    /// `fc`, `ft` or `tc`.
    pub output: String,
    /// Uncut chip thickness, mm.
    pub uncut_mm: f64,
    /// Speed, m/min.
    pub speed_m_min: f64,
    /// Before, %.
    pub before_pct: f64,
    /// After, %.
    pub after_pct: f64,
}

/// The global misfit test of the baseline with the assumed noise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GlobalMisfit {
    /// Sum of squared noise-unit residuals.
    pub chi2: f64,
    /// Degrees of freedom (observations - baseline parameters, at least 1).
    pub dof: usize,
    /// Chi-square upper-tail probability.
    pub p_value: f64,
}

/// The decision thresholds in force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Thresholds {
    /// Family-wise false-positive rate aimed at.
    pub family_alpha: f64,
    /// Per-mechanism significance level (calibrated on the null replicates; Bonferroni without them).
    pub per_mechanism_alpha: f64,
    /// Number of mechanisms tested in the first round.
    pub mechanisms_tested: usize,
    /// Cosine above which two mechanisms' fitted corrections count as near-equivalent.
    pub ambiguity_cosine: f64,
    /// AICc difference below which a rival is near-equivalent.
    pub ambiguity_delta_aicc: f64,
}

/// A mechanism that could not be tested on this design, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NotTestable {
    /// Id.
    pub id: String,
    /// Reason.
    pub reason: String,
}

/// The full diagnosis report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Overall verdict.
    pub verdict: Verdict,
    /// Located mismatch per output (baseline residuals).
    pub mismatch: Vec<Mismatch>,
    /// Refitted mechanisms, best first.
    pub mechanisms: Vec<MechanismResult>,
    /// Accepted mechanism ids.
    pub selected: Vec<String>,
    /// Near-equivalent mechanism ids when the verdict is ambiguous.
    pub ambiguous_with: Vec<String>,
    /// Fit before and after.
    pub fit: FitSummary,
    /// The test or measurement that would separate the remaining candidates.
    pub next_test: String,
    /// Plain-text explanation.
    pub explanation: String,
    /// `A` (external simulation) or `B` (own forward model).
    pub mode: String,
    /// Number of test conditions.
    pub conditions: usize,
    /// Number of measured numbers.
    pub observations: usize,
    /// Assumed relative noise per output, %.
    pub noise_pct: [f64; crate::fit::NOUT],
    /// Global misfit of the baseline.
    pub global_misfit: GlobalMisfit,
    /// Decision thresholds.
    pub thresholds: Thresholds,
    /// Baseline parameters before (fitted baseline) and after (with the selected mechanisms).
    pub baseline_params_before: Vec<NamedValue>,
    /// Baseline parameters after the joint refit.
    pub baseline_params_after: Vec<NamedValue>,
    /// Mechanisms not testable on this design, or whose screen or refit failed (with the reason).
    pub not_testable: Vec<NotTestable>,
    /// Fits that did not converge cleanly (iteration cap, damped rerun, nothing fitted), named.
    #[serde(default)]
    pub fit_notes: Vec<String>,
    /// Conditions far from the rest after the final model (`crate::far`; a note, not a decision).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub far_conditions: Vec<crate::far::FarCondition>,
    /// Residuals before and after (for plots).
    pub residuals: Vec<ResidualRow>,
    /// Where the noise level of Fc, Ft, t2 came from (per-row sd, repeats, or the default).
    #[serde(default)]
    pub noise_source: Vec<String>,
    /// How the significance level was set (calibrated null or Bonferroni).
    #[serde(default)]
    pub calibration: String,
    /// Notes about the simulator (Mode A: the shadow fit of the external simulation).
    #[serde(default)]
    pub simulator_notes: Vec<String>,
    /// Mode A: RMS (%) of the fitted shadow against the external simulation over the tests it
    /// solves; absent in Mode B and when no shadow was built.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_rms_pct: Option<f64>,
    /// Mode A: the fitted shadow's tool-chip interface factor m_f (tau_int = m_f k_chip; 1 =
    /// Oxley's sticking, kept unless a lower m_f halves the misfit); absent in Mode B and when no
    /// shadow was built.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_friction_factor: Option<f64>,
    /// Mode A: the fitted shadow's own cutting-edge radius, um (0 = sharp; kept only where a
    /// radius halves the misfit and brings the shadow within 6 %: the simulation carries ploughing
    /// forces); absent in Mode B and when no shadow was built.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_edge_radius_um: Option<f64>,
    /// Mode A: the fitted shadow's scale on Oxley's strain-rate constant C0 (1 = Oxley's
    /// normal-stress condition, kept unless a scale halves the misfit: the simulation's primary
    /// zone is not Oxley's); absent in Mode B and when no shadow was built.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_c0_scale: Option<f64>,
}

impl Report {
    /// A readable multi-line text report.
    #[must_use]
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Discrepancy diagnosis (mode {}): {} conditions, {} measured numbers",
            self.mode, self.conditions, self.observations
        );
        let _ = writeln!(s, "Verdict: {}", self.verdict.as_str());
        let _ = writeln!(
            s,
            "Global misfit of the baseline: chi2 = {:.1} on {} dof (p = {:.2e}, noise Fc {:.1} %, Ft {:.1} %, tc {:.1} %, T_int rise {:.0} %)",
            self.global_misfit.chi2, self.global_misfit.dof, self.global_misfit.p_value, self.noise_pct[0], self.noise_pct[1], self.noise_pct[2], self.noise_pct[3]
        );
        for (o, src) in ["Fc", "Ft", "tc", "T_int"].iter().zip(&self.noise_source) {
            let _ = writeln!(s, "  noise of {o}: {src}");
        }
        for n in &self.simulator_notes {
            let _ = writeln!(s, "Simulator: {n}");
        }
        let _ = writeln!(s, "\nWhere the model misses (measured - model):");
        for m in &self.mismatch {
            let _ = writeln!(
                s,
                "  {:<3} bias {:+7.1} %  trend: {}  p = {:.2e}  tests: {}",
                m.output,
                m.bias_pct,
                m.trend,
                m.p_value,
                if m.tests.is_empty() { "-".to_string() } else { m.tests.join(", ") }
            );
        }
        let _ = writeln!(
            s,
            "\nMechanisms refitted jointly with the baseline (threshold p < {:.2e} per mechanism; {}):",
            self.thresholds.per_mechanism_alpha, self.calibration
        );
        for m in &self.mechanisms {
            let params = params_text(m);
            let ho = match (m.heldout_rms_before, m.heldout_rms_after) {
                (Some(b), Some(a)) => format!("held-out RMS {b:.1} % -> {a:.1} %"),
                _ => "held-out: not available".into(),
            };
            let _ = writeln!(
                s,
                "  {} {:<20} dAICc {}  p = {}  explains {:3.0} %  {}  {}\n      {}",
                if m.accepted { "[accepted]" } else { "[        ]" },
                m.id,
                m.delta_aicc.map_or_else(|| "not available (n <= k + 1)".to_string(), |v| format!("{v:+7.1}")),
                m.p_value.map_or_else(|| "not available (too few numbers)".to_string(), |v| format!("{v:.2e}")),
                100.0 * m.explained_fraction,
                ho,
                params,
                m.reason
            );
            if !m.detection_limits.is_empty() {
                let _ = writeln!(
                    s,
                    "      detected with 80 % power beyond: {}",
                    crate::detect::limits_text(&m.detection_limits)
                );
            }
        }
        if !self.not_testable.is_empty() {
            let _ = writeln!(
                s,
                "  not testable here: {}",
                self.not_testable.iter().map(|n| format!("{} ({})", n.id, n.reason)).collect::<Vec<_>>().join("; ")
            );
        }
        for note in &self.fit_notes {
            let _ = writeln!(s, "  fit note: {note}");
        }
        let row = |r: &OutputRms| {
            let f = |v: Option<f64>| v.map(|x| format!("{x:6.1}")).unwrap_or_else(|| "     -".into());
            format!("Fc {} Ft {} tc {}  all {:6.1}", f(r.fc), f(r.ft), f(r.tc), r.all)
        };
        let _ = writeln!(s, "\nRMS error %            before                                   after");
        let _ = writeln!(s, "  in-sample   {}   {}", row(&self.fit.before.in_sample), row(&self.fit.after.in_sample));
        if let (Some(b), Some(a)) = (&self.fit.before.loco, &self.fit.after.loco) {
            let _ = writeln!(s, "  held-out    {}   {}", row(b), row(a));
        }
        if !self.selected.is_empty() {
            let _ = writeln!(s, "\nSelected: {}", self.selected.join(", "));
        }
        if !self.ambiguous_with.is_empty() {
            let _ = writeln!(s, "\nCandidates that cannot be told apart here: {}", self.ambiguous_with.join(", "));
        }
        let _ = writeln!(s, "\nNext test: {}", self.next_test);
        let _ = writeln!(s, "\n{}", self.explanation);
        s
    }
}

/// A mechanism's parameters with their intervals, for the text report. A note that all of them
/// share (one refit, one covariance) is printed once, after them.
fn params_text(m: &MechanismResult) -> String {
    let shared = m.params.values().next().map(|v| v.ci_note.as_str()).filter(|n| {
        !n.is_empty()
            && m.params.len() > 1
            && m.params.values().all(|v| v.ci_note == *n && v.ci_low.is_some() && v.ci_high.is_some())
    });
    let mut params: Vec<String> = m
        .params
        .iter()
        .map(|(k, v)| match (v.ci_low, v.ci_high) {
            (Some(l), Some(h)) if v.ci_note.is_empty() || shared.is_some() => {
                format!("{k} = {:.4} {} [{l:.4}, {h:.4}]", v.value, v.unit)
            }
            (Some(l), Some(h)) => format!("{k} = {:.4} {} [{l:.4}, {h:.4}] ({})", v.value, v.unit, v.ci_note),
            _ => format!("{k} = {:.4} {} (interval not available: {})", v.value, v.unit, v.ci_note),
        })
        .collect();
    if let Some(n) = shared {
        params.push(format!("({n})"));
    }
    params.join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mechanism(notes: [&str; 2]) -> MechanismResult {
        let pv = |value: f64, note: &str| ParamValue {
            value,
            unit: "-".into(),
            ci_low: Some(value - 0.1),
            ci_high: Some(value + 0.1),
            ci_note: note.into(),
        };
        MechanismResult {
            id: "heat_partition".into(),
            accepted: false,
            params: [("k_beta".to_string(), pv(1.5, notes[0])), ("s_int".to_string(), pv(0.8, notes[1]))]
                .into_iter()
                .collect(),
            delta_aicc: Some(-3.0),
            p_value: Some(0.01),
            heldout_rms_before: None,
            heldout_rms_after: None,
            explained_fraction: 0.3,
            absorption: 0.1,
            screen_p_value: Some(0.02),
            reason: String::new(),
            detection_limits: Vec::new(),
        }
    }

    #[test]
    fn a_note_the_parameters_share_is_printed_once() {
        let text = params_text(&mechanism(["joint", "joint"]));
        assert_eq!(text, "k_beta = 1.5000 - [1.4000, 1.6000]; s_int = 0.8000 - [0.7000, 0.9000]; (joint)");
        let own = params_text(&mechanism(["", "at its bound"]));
        assert_eq!(own, "k_beta = 1.5000 - [1.4000, 1.6000]; s_int = 0.8000 - [0.7000, 0.9000] (at its bound)");
    }
}
