//! The diagnosis algorithm: baseline fit -> locate -> screen -> joint refit -> decide (`crate::verdict`) -> report
//! (design note Sec 3.2-3.9).
//!
//! Acceptance of a mechanism needs all of: (1) an F-test of the joint refit below the level
//! calibrated on the data's own null, and an AICc below the current model's (`ftest::supported`;
//! `crate::null`: parametric bootstrap through the whole screen
//! and refit; the family level divided by the number of mechanisms, Bonferroni, only when no
//! replicates are asked for; the chi-bar-square mixture for parameters whose off value sits on a
//! bound, Self & Liang 1987); (2) a lower leave-one-condition-out error than the baseline, for
//! the mechanism and for the nested selection pipeline; (3) residual degrees of freedom for its
//! 95 % intervals (reported, with a note when no single interval of a strength excludes its off
//! value or a strength sits at its far bound; the joint F-test decides) and, for softening, no
//! crossing of its two forms; (4) no rival within 2 AICc whose
//! fitted correction has a cosine above 0.9 with it. In-sample improvement alone never suffices.
//! The candidate set of the nested pipeline is taken from the full-data screen (the per-fold
//! decision is re-run, the screen is not): a stated, small optimism.

use cutcal_model::CuttingTest;

use crate::error::DiagnoseError;
use crate::fit::{observations, Spec, OUTPUTS};
use crate::heldout::heldout_round;
use crate::instrument::stops_claim;
use crate::locate::locate;
use crate::mechanism::{info, testable, Context, MechanismId};
use crate::narrative::{explain, result_of, simulator_notes};
use crate::next_test::next_test;
use crate::problem::{condition_groups, loco_of, rms_pct, Candidate, Loco, Problem};
use crate::report::*;
use crate::screen::{cosine, screen_and_refit};
use crate::separate::{own_test, separating_test, Recorded};
use crate::simulator::Simulator;
use crate::stats;
use crate::verdict::decide;

/// Settings of one diagnosis; no `Default`: the noise levels are a statement about the data.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// Assumed relative noise of Fc, Ft, tc (design note Sec 3.1 defaults: 0.03, 0.05, 0.05) and of
    /// the interface temperature rise over 20 degC (0.10), used where the data do not state theirs.
    pub noise: [f64; crate::fit::NOUT],
    /// Family-wise false-positive rate aimed at (0.05).
    pub family_alpha: f64,
    /// Cosine above which two fitted corrections are near-equivalent (0.9, note Sec 3.4).
    pub ambiguity_cosine: f64,
    /// AICc difference below which a rival is near-equivalent (2, note Sec 3.6).
    pub ambiguity_delta_aicc: f64,
    /// Iteration cap of each least-squares fit.
    pub max_iterations: usize,
    /// `A` or `B`, for the report.
    pub mode: String,
    /// Library mechanisms to consider.
    pub mechanisms: Vec<MechanismId>,
    /// Null replicates of the calibrated significance level (0: Bonferroni, stated in the report).
    pub null_replicates: usize,
    /// Seed of the null replicates.
    pub seed: u64,
    /// Notes about the simulator (e.g. the shadow fit of Mode A) carried into the report.
    pub simulator_notes: Vec<String>,
}

impl Config {
    /// The design note's defaults for `mode` (`A` or `B`) with the whole library.
    #[must_use]
    pub fn standard(mode: &str) -> Self {
        Self {
            // Interface temperature rise: 10 % (thermocouple / infrared measurements of the
            // tool-chip interface scatter by about that much).
            noise: [0.03, 0.05, 0.05, 0.10],
            family_alpha: 0.05,
            ambiguity_cosine: 0.9,
            ambiguity_delta_aicc: 2.0,
            max_iterations: 40,
            mode: mode.to_string(),
            mechanisms: MechanismId::ALL.to_vec(),
            // Mode A runs on the shadow's tables (a replicate costs milliseconds); Mode B runs the
            // full Oxley model (about 1 s for 200 replicates of 4 conditions, docs/diagnosis.md).
            null_replicates: 200,
            seed: 2024,
            simulator_notes: Vec::new(),
        }
    }
}

/// Diagnoses the discrepancy between `sim` and the recordings in `tests`.
///
/// Returns an error if nothing was measured, or the baseline cannot be simulated.
pub fn diagnose(sim: &dyn Simulator, tests: &[CuttingTest], cfg: &Config) -> Result<Report, DiagnoseError> {
    // A measured interface temperature is used only when the simulator gives one at every test; the
    // simulated one also lets its scatter be read from neighbouring conditions (`crate::noise`).
    let stripped: Vec<CuttingTest>;
    let mut tests = tests;
    let mut t_int_sim: Option<Vec<f64>> = None;
    if tests.iter().any(|t| t.measured.interface_temperature_c.is_some()) {
        let start: Vec<f64> = sim.baseline_params().iter().map(|p| p.start).collect();
        t_int_sim = (sim.simulate(tests, &start, &vec![crate::hooks::Hooks::NEUTRAL; tests.len()]).ok())
            .and_then(|p| p.iter().map(|p| p.t_int_c).collect());
        if t_int_sim.is_none() {
            stripped = tests
                .iter()
                .map(|t| {
                    let mut t = t.clone();
                    t.measured.interface_temperature_c = None;
                    t
                })
                .collect();
            tests = &stripped;
        }
    }
    let obs = observations(tests);
    if obs.is_empty() {
        return Err(DiagnoseError::Inconsistent("no measured force or chip thickness in the recordings".into()));
    }
    let groups = condition_groups(tests);
    let noise_model = crate::noise::from_data(tests, &groups, cfg.noise, t_int_sim.as_deref());
    let cfg = &Config { noise: noise_model.sd, ..cfg.clone() };
    let pr = Problem { sim, tests, obs, groups, cfg };
    // The optional measurements every test holds, for the separating advice of the report.
    let rec = Recorded::of(tests);
    let n = pr.n();
    let noise = cfg.noise;
    let ctx0 = Context::of(tests).with_baseline_interface(sim, tests);
    let base_spec = Spec { mechanisms: Vec::new(), ctx: ctx0.clone() };
    let base = pr.fit(&base_spec, None)?;
    let mut fit_notes: Vec<String> = Vec::new();
    if let Some(note) = base.status.note() {
        fit_notes.push(format!("baseline fit: {note}"));
    }
    let dof = n.saturating_sub(base.k).max(1);
    let global = GlobalMisfit { chi2: base.rss, dof, p_value: stats::chi2_sf(base.rss, dof as f64) };
    let mismatch = locate(tests, &pr.obs, &base.preds, &noise);

    // Which mechanisms can be tested at all.
    let mut usable = Vec::new();
    let mut not_testable = Vec::new();
    for &m in &cfg.mechanisms {
        match testable(m, tests, &ctx0, sim) {
            Ok(()) => usable.push(m),
            Err(reason) => not_testable.push(NotTestable { id: m.as_str().into(), reason }),
        }
    }
    let k_tested = usable.len().max(1);
    let calibration = if cfg.null_replicates > 0 && !usable.is_empty() {
        Some(crate::null::calibrate(&pr, &base, &base_spec, &usable, cfg.null_replicates, cfg.seed))
    } else {
        None
    };
    let alpha_k = calibration.as_ref().map_or(cfg.family_alpha / k_tested as f64, |c| c.alpha);
    let calibration_text = match &calibration {
        Some(c) => format!(
            "calibrated on {} null replicates from the fitted baseline through screen, refit and interval checks \
             ({} failed, counted as claims); {} of them would claim at the family level {}",
            c.replicates, c.failed, c.claims_at_family_level, cfg.family_alpha
        ),
        None => {
            format!("Bonferroni: family level {} over {} mechanisms (no null replicates)", cfg.family_alpha, k_tested)
        }
    };
    let conditions = pr.groups.len();
    let cap = if conditions <= 10 {
        1
    } else if conditions <= 20 {
        2
    } else {
        3
    };

    let base_specs = [(&base_spec, base.x.as_slice())];
    let base_loco_folds = pr.loco(&base_specs)?;
    let base_loco = base_loco_folds.as_ref().map(|f| loco_of(f, 0));

    let mut current = base.clone();
    let mut current_spec = base_spec.clone();
    let mut current_loco = base_loco.clone();
    let mut accepted: Vec<MechanismId> = Vec::new();
    let mut all_results: Vec<MechanismResult> = Vec::new();
    let mut ambiguous: Vec<MechanismId> = Vec::new();
    let mut first_round: Vec<Candidate> = Vec::new();
    let mut nested_loco: Option<Loco> = base_loco.clone();
    let mut notes: Vec<String> = Vec::new();

    for round in 0..cap {
        let remaining: Vec<MechanismId> =
            usable.iter().copied().filter(|m| !current_spec.mechanisms.contains(m)).collect();
        if remaining.is_empty() {
            break;
        }
        let (mut cands, lost) = screen_and_refit(&pr, &current, &current_spec, &remaining)?;
        for mut l in lost {
            if round > 0 {
                l.reason = format!("round {}: {}", round + 1, l.reason);
            }
            not_testable.push(l);
        }
        for c in &cands {
            if let Some(note) = c.fit.status.note() {
                fit_notes.push(format!("refit with {}: {note}", c.id.as_str()));
            }
        }
        // Significance, interval.
        // Later rounds add a second or third mechanism on top of a claim: the calibrated level was
        // set for the first claim, so each further round divides it by 4 (a stated, conservative
        // choice that keeps spurious additions rare).
        let alpha_round = alpha_k / f64::from(1u32 << (2 * round as u32));
        for c in &mut cands {
            c.significant = crate::ftest::supported(c.p, alpha_round, c.daicc);
        }
        // A later round does not claim a confounder of a mechanism already claimed (either one
        // listed in the other's `confounders`): their signatures share directions, so what is
        // left after the first claim is as likely the first mechanism's true form differing from
        // the library's as a second mechanism, and the data cannot apportion the two.
        let confounded_with = |id: MechanismId| {
            accepted.iter().copied().find(|&a| info(a).confounders.contains(&id) || info(id).confounders.contains(&a))
        };
        // Held-out check for the significant ones, with the nested selection pipeline.
        let nested_before = nested_loco.clone();
        let sig: Vec<usize> = (0..cands.len()).filter(|&i| cands[i].significant && cands[i].ci_ok).collect();
        if !sig.is_empty() {
            let refused = |id: MechanismId| confounded_with(id).is_some();
            let current_pair = (&current_spec, &current);
            if let Some(l) =
                heldout_round(&pr, &mut cands, &sig, current_pair, current_loco.as_ref(), alpha_round, &refused)?
            {
                nested_loco = Some(l);
            }
        }
        let before_rss = current_loco.as_ref().map(|l| l.rss);
        let carried = |c: &Candidate| crate::heldout::carried(pr.groups.len(), c);
        let nested_ok = match (&nested_loco, before_rss) {
            (Some(nl), Some(b)) => nl.rss <= b,
            _ => false,
        };
        for c in &mut cands {
            c.accepted = false;
            c.reason = if !c.p.is_finite() {
                "too few numbers to test it".into()
            } else if !c.significant {
                crate::ftest::unsupported_reason(c.p, alpha_round, c.daicc)
            } else if let Some(why) = &c.conflict {
                why.clone()
            } else if !c.ci_ok {
                "interval includes the off value or the estimate sits on a bound".into()
            } else {
                match (&c.loco_after, before_rss) {
                    (Some(a), Some(b)) if a.rss < b && nested_ok && !carried(c) => {
                        "passes significance, interval and held-out checks".into()
                    }
                    (Some(a), Some(b)) if a.rss < b && nested_ok => crate::heldout::carried_reason(c),
                    (Some(a), Some(b)) => crate::heldout::failure_reason(a.rss, b, nested_loco.as_ref().map(|l| l.rss)),
                    _ => "held-out validation impossible with fewer than 3 conditions".into(),
                }
            };
        }
        for c in &mut cands {
            if let Some(a) = confounded_with(c.id).filter(|_| c.reason.starts_with("passes")) {
                let sep = separating_test(a, c.id, rec).unwrap_or_else(|| own_test(c.id, rec));
                notes.push(format!(
                    "{} also improves the fit on top of {} (p = {:.2e}), but the library lists the two as \
                     confounded, so it is not claimed as a second mechanism: what remains may be {}'s true form. \
                     To separate them: {}.",
                    c.id.as_str(),
                    a.as_str(),
                    c.p,
                    a.as_str(),
                    sep
                ));
                c.reason = format!(
                    "confounded with {}, claimed in an earlier round: not claimed as a second mechanism (the \
                     remaining misfit may be {}'s true form; to separate them: {})",
                    a.as_str(),
                    a.as_str(),
                    sep
                );
                c.held_back_for = Some(a);
            }
        }
        let eligible: Vec<usize> = (0..cands.len())
            .filter(|&i| {
                let c = &cands[i];
                c.significant
                    && c.ci_ok
                    && matches!((&c.loco_after, before_rss), (Some(a), Some(b)) if a.rss < b)
                    && nested_ok
                    && !carried(c)
                    && confounded_with(c.id).is_none()
            })
            .collect();
        let mut best = eligible.iter().copied().min_by(|&a, &b| cands[a].daicc.total_cmp(&cands[b].daicc));
        if let Some((b, h)) = best.and_then(|b| crate::verdict::outdone_by_held_back(&cands, b).map(|h| (b, h))) {
            let (held, daicc) = (cands[h].id.as_str(), cands[h].daicc);
            cands[b].reason = format!(
                "not claimed: {held}, held back as a confounder of an earlier claim, explains the remaining misfit better (dAICc {daicc:.1} against {:.1}), so what remains is more likely that claim's own form",
                cands[b].daicc
            );
            best = None;
        }
        let mut chosen = None;
        // Instrument explanations compete with the best mechanism (`crate::instrument`).
        let stopped = best.is_some_and(|b| {
            let current_pair = (&current_spec, &current);
            stops_claim(&pr, current_pair, &mut cands, b, alpha_round, &mut notes)
        });
        if let Some(b) = best.filter(|_| !stopped) {
            let rivals: Vec<usize> = (0..cands.len())
                .filter(|&i| {
                    i != b
                        && cands[i].significant
                        && cands[i].conflict.is_none()
                        && cands[i].daicc - cands[b].daicc < cfg.ambiguity_delta_aicc
                        && cosine(&cands[i].change, &cands[b].change) > cfg.ambiguity_cosine
                })
                .collect();
            if rivals.is_empty() {
                chosen = Some(b);
            } else if round == 0 {
                ambiguous.push(cands[b].id);
                for &r in &rivals {
                    ambiguous.push(cands[r].id);
                    cands[r].reason = format!("near-equivalent to {}", cands[b].id.as_str());
                }
                cands[b].reason = format!(
                    "near-equivalent rival(s): {}",
                    rivals.iter().map(|&r| cands[r].id.as_str()).collect::<Vec<_>>().join(", ")
                );
            }
        }
        if let Some(b) = chosen {
            cands[b].accepted = true;
            accepted.push(cands[b].id);
        }
        for c in &cands {
            all_results.push(result_of(c, base_loco.as_ref(), &pr.obs, &noise, alpha_round));
        }
        match chosen {
            Some(b) => {
                current = cands[b].fit.clone();
                current_spec = cands[b].spec.clone();
                current_loco = cands[b].loco_after.clone();
                if round == 0 {
                    first_round = cands;
                }
            }
            None => {
                if round == 0 {
                    first_round = cands;
                } else {
                    // The round claimed nothing: the held-out error of the selection is the previous
                    // round's (this round's nested pipeline chose among candidates not claimed).
                    nested_loco = nested_before;
                }
                break;
            }
        }
    }

    // Verdict.
    let verdict =
        decide(&accepted, &mut ambiguous, base_loco.is_some(), &global, &mismatch, &first_round, &pr.obs, &base);
    all_results.sort_by(|a, b| {
        let key = |m: &MechanismResult| m.delta_aicc.unwrap_or(f64::INFINITY);
        b.accepted.cmp(&a.accepted).then(key(a).total_cmp(&key(b)))
    });

    let outputs: Vec<usize> = pr.obs.iter().map(|o| o.output).collect();
    let after_fit = &current;
    let summary = FitSummary {
        before: FitStats {
            in_sample: rms_pct(&base.resid, &outputs, &noise),
            loco: base_loco.as_ref().map(|l| rms_pct(&l.resid, &outputs, &noise)),
        },
        after: FitStats {
            in_sample: rms_pct(&after_fit.resid, &outputs, &noise),
            loco: if accepted.is_empty() {
                base_loco.as_ref().map(|l| rms_pct(&l.resid, &outputs, &noise))
            } else {
                nested_loco.as_ref().map(|l| rms_pct(&l.resid, &outputs, &noise))
            },
        },
    };
    let names: Vec<String> = sim.baseline_params().iter().map(|p| p.name.clone()).collect();
    let named = |x: &[f64]| names.iter().zip(x).map(|(n, v)| NamedValue { name: n.clone(), value: *v }).collect();
    let residuals: Vec<ResidualRow> = pr
        .obs
        .iter()
        .enumerate()
        .map(|(i, o)| ResidualRow {
            test: tests[o.test].id.clone(),
            output: OUTPUTS[o.output].into(),
            uncut_mm: tests[o.test].uncut_chip_thickness_m * 1e3,
            speed_m_min: tests[o.test].speed_m_per_s * 60.0,
            before_pct: 100.0 * ((base.resid[i] * noise[o.output]).exp() - 1.0),
            after_pct: 100.0 * ((after_fit.resid[i] * noise[o.output]).exp() - 1.0),
        })
        .collect();
    let next_test = next_test(
        &pr,
        verdict,
        &accepted,
        &ambiguous,
        &first_round,
        &base,
        &base_spec,
        &current,
        &current_spec,
        alpha_k,
    );
    let mut explanation =
        explain(verdict, &mismatch, &accepted, &ambiguous, &first_round, &summary, conditions, &global, rec, alpha_k);
    notes.extend(crate::separate::interface_noise_note(verdict, rec, noise_model.assumed[3], noise[3]));
    let far_conditions = crate::far::far_conditions(&residuals, &noise);
    notes.extend(crate::far::far_sentence(&far_conditions));
    for note in &notes {
        explanation.push(' ');
        explanation.push_str(note);
    }
    Ok(Report {
        verdict,
        mismatch,
        mechanisms: all_results,
        selected: accepted.iter().map(|m| m.as_str().to_string()).collect(),
        ambiguous_with: ambiguous.iter().map(|m| m.as_str().to_string()).collect(),
        fit: summary,
        next_test,
        explanation,
        mode: cfg.mode.clone(),
        conditions,
        observations: n,
        noise_pct: noise.map(|s| 100.0 * s),
        global_misfit: global,
        thresholds: Thresholds {
            family_alpha: cfg.family_alpha,
            per_mechanism_alpha: alpha_k,
            mechanisms_tested: k_tested,
            ambiguity_cosine: cfg.ambiguity_cosine,
            ambiguity_delta_aicc: cfg.ambiguity_delta_aicc,
        },
        baseline_params_before: named(&base.x),
        baseline_params_after: named(&current.x),
        not_testable,
        fit_notes,
        far_conditions,
        residuals,
        noise_source: noise_model.source.to_vec(),
        calibration: calibration_text,
        simulator_notes: simulator_notes(&cfg.simulator_notes, &ctx0, &usable, tests.len()),
        shadow_rms_pct: None,
        shadow_friction_factor: None,
        shadow_edge_radius_um: None,
        shadow_c0_scale: None,
    })
}
