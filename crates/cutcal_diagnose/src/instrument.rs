//! Instrument explanations as competitors (issue 10, decoys): before a mechanism is claimed, the
//! mismatch must be explained better by it than by an artefact of the measurement chain.
//!
//! The artefacts are fitted jointly with the current model (baseline, nuisance and the mechanisms
//! already accepted), each with one parameter `g`:
//!
//! - **force gain**: both force channels scaled by one factor `exp(g)` (a calibration error of the
//!   dynamometer's charge amplifier acts on both channels alike, ISO 21612:2021 Sec 5); the chip
//!   thickness and the temperature are untouched, unlike a flow-stress level;
//! - **one channel's gain**: the cutting-force or the feed-force channel alone scaled by `exp(g)`
//!   (each channel of a multi-channel charge amplifier has its own sensitivity setting, so one can
//!   be set or calibrated wrong alone). A cross-talk adds a share of the *other* channel, whose
//!   ratio to this one changes over the conditions (Ft/Fc falls with the feed), so the two separate
//!   where the data span such a change;
//! - **force drift**: both force channels scaled by `exp(g s_i)` with `s_i` the run-order state of
//!   test i (charge-amplifier drift grows with time and acts on both channels alike). A flank wear
//!   land instead raises the feed force relatively more than the cutting force (land normal stress
//!   against land shear, Smithey, Kapoor & DeVor 2001) and moves the chip, so the two separate
//!   where the data carry that signature.
//!
//! Inside its bound `g` is a nuisance of the measurement chain and pays a prior of sd half the
//! bound, as the shadow's nuisance does; whether it sits on the bound is judged without the prior.
//! Against the cross-talk, itself an artefact of the measurement chain that pays no prior, the
//! artefacts compete without theirs: one instrument explanation against another on equal terms.
//!
//! A mechanism whose refit does not beat an artefact by the AICc margin of the ambiguity rule
//! (Burnham & Anderson 2002: a difference below 2 is no support for either) is not claimed; the
//! report names the artefact. This rule only removes claims, so the calibrated family-wise level
//! of `crate::null` still bounds the false-positive rate.

use cutcal_ident::lm::{minimise, Bounds, LmOptions, Problem as LmProblem};
use cutcal_ident::IdentError;
use nalgebra::DVector;

use crate::error::DiagnoseError;
use crate::fit::{self, layout, Fit, Spec};
use crate::mechanism::MechanismId;
use crate::problem::{Candidate, Problem};
use crate::screen::{boundary_params, f_test, grid_chosen, tested_df};
use crate::stats;

/// An instrument artefact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Artefact {
    /// One gain on both force channels.
    Gain,
    /// One gain on the cutting-force channel alone.
    CuttingGain,
    /// One gain on the feed-force channel alone.
    FeedGain,
    /// A drift of both force channels over the run order.
    Drift,
}

impl Artefact {
    /// Plain-language name for the report.
    pub(crate) fn describe(self) -> &'static str {
        match self {
            Artefact::Gain => "a common gain error of both force channels",
            Artefact::CuttingGain => "a gain error of the cutting-force channel alone",
            Artefact::FeedGain => "a gain error of the feed-force channel alone",
            Artefact::Drift => "a drift of both force channels over the run order",
        }
    }

    /// Which force channels the artefact scales: (cutting, feed) as 1 or 0.
    fn channels(self) -> [f64; 2] {
        match self {
            Artefact::Gain | Artefact::Drift => [1.0, 1.0],
            Artefact::CuttingGain => [1.0, 0.0],
            Artefact::FeedGain => [0.0, 1.0],
        }
    }
}

/// A fitted artefact.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ArtefactFit {
    /// Which artefact.
    pub(crate) artefact: Artefact,
    /// Its fitted parameter `g` (ln of the gain, or of the gain at the last test).
    pub(crate) g: f64,
    /// Sum of squared data residuals, noise units.
    pub(crate) rss: f64,
    /// Sum of squared prior pseudo-residuals of the nuisance, and of the artefact's own when
    /// `prior`.
    pub(crate) penalty: f64,
    /// Parameters of the fit (current model + 1).
    pub(crate) k: usize,
    /// Whether the artefact's own prior ([`G_PRIOR_SD`]) entered the fit and `penalty`.
    pub(crate) prior: bool,
}

impl ArtefactFit {
    /// Whether the fitted factor lies inside its bound. A fit that presses against the bound wants a
    /// gain (or drift) beyond what a calibrated dynamometer can be off by ([`G_BOUND`]): that is a
    /// physical mismatch, not an instrument explanation, so it may not stop a claim.
    pub(crate) fn within_bound(&self) -> bool {
        self.g.abs() < G_BOUND * (1.0 - 1e-3)
    }

    /// The report's note for an artefact on its bound that would otherwise have stopped the claim
    /// of `mechanism`.
    pub(crate) fn on_bound_note(&self, mechanism: &str) -> String {
        format!(
            "Instrument check: {} would explain the mismatch about as well as {mechanism} only with a factor of \
             {:.3}, on its bound; a calibrated dynamometer is not that far off, so it does not stop the claim.",
            self.artefact.describe(),
            self.g.exp()
        )
    }

    /// AICc of the fit on `n` observations.
    pub(crate) fn aicc(&self, n: usize) -> f64 {
        stats::aicc(self.rss + self.penalty, n, self.k)
    }
}

/// Bound of the artefact parameter, ln(1.2): a force channel whose gain is off (or drifts) by more
/// than 20 % fails any static check with dead weights (ISO 376 class-2 force calibration is within
/// 0.5 %), so a larger factor is not an instrument explanation but a physical mismatch.
const G_BOUND: f64 = 0.182_321_556_793_954_6;

/// Prior standard deviation of the artefact parameter: half its bound, the rule of every nuisance
/// prior (`crate::nuisance`). A calibration error is a nuisance of the measurement chain; its
/// pseudo-residual `g / G_PRIOR_SD` enters the fit and the AICc as the nuisance priors' do.
const G_PRIOR_SD: f64 = 0.5 * G_BOUND;

struct ArtefactProblem<'a> {
    pr: &'a Problem<'a>,
    spec: &'a Spec,
    /// Per-test exponent basis of the force factor `exp(g b_i)`.
    basis: Vec<f64>,
    /// The channels the factor scales ([`Artefact::channels`]).
    channels: [f64; 2],
    /// Whether the artefact parameter carries its prior pseudo-residual `g / G_PRIOR_SD`.
    prior: bool,
}

impl LmProblem for ArtefactProblem<'_> {
    fn parameter_count(&self) -> usize {
        layout(self.pr.sim, self.spec).0.len() + 1
    }
    fn residual_count(&self) -> usize {
        self.pr.obs.len()
            + self.pr.sim.baseline_params().iter().filter(|p| p.prior_sd.is_some()).count()
            + usize::from(self.prior)
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let x: Vec<f64> = p.iter().copied().collect();
        let (model, g) = x.split_at(x.len() - 1);
        let mut preds =
            fit::predict(self.pr.sim, self.pr.tests, self.spec, &self.spec.ctx, model).map_err(|e| match e {
                DiagnoseError::Model { source, .. } => IdentError::Model(source),
                other => IdentError::InvalidOptions(other.to_string()),
            })?;
        let [on_fc, on_ft] = self.channels;
        for (pd, b) in preds.iter_mut().zip(&self.basis) {
            pd.fc_n_per_m *= (g[0] * b * on_fc).exp();
            pd.ft_n_per_m *= (g[0] * b * on_ft).exp();
        }
        let r = fit::residuals(&self.pr.obs, &preds, &self.pr.cfg.noise);
        for (i, v) in r.iter().enumerate() {
            out[i] = *v;
        }
        let mut k = r.len();
        for (i, ps) in self.pr.sim.baseline_params().iter().enumerate() {
            if let Some(sd) = ps.prior_sd {
                out[k] = (x[i] - ps.start) / sd;
                k += 1;
            }
        }
        if self.prior {
            out[k] = g[0] / G_PRIOR_SD;
        }
        Ok(())
    }
}

/// Fits each artefact that this design can show on top of `current` (model `spec`). An artefact
/// whose fit fails is left out (it can then not stop a claim; the mechanism's own checks stand);
/// the caller leaves out those whose factor sits on its bound ([`ArtefactFit::within_bound`]).
/// Whether the factor sits on its bound is the data's own answer, without the prior; one inside
/// it is refitted with its prior when `with_prior`, whose cost then counts in the AICc as the
/// nuisance priors' do (a fit that fails with the prior keeps the one without, which stops claims
/// more readily). Without `with_prior` (against the cross-talk) every fit is the free one.
pub(crate) fn fit_artefacts(pr: &Problem<'_>, current: &Fit, spec: &Spec, with_prior: bool) -> Vec<ArtefactFit> {
    let mut kinds = vec![Artefact::Gain];
    let recorded = |f: fn(&cutcal_model::Measured) -> Option<f64>| pr.tests.iter().any(|t| f(&t.measured).is_some());
    if recorded(|m| m.cutting_force_n_per_m) && recorded(|m| m.feed_force_n_per_m) {
        kinds.extend([Artefact::CuttingGain, Artefact::FeedGain]);
    }
    if spec.ctx.wear_state.is_some() {
        kinds.push(Artefact::Drift);
    }
    kinds
        .into_iter()
        .filter_map(|a| {
            let free = fit_artefact(pr, spec, &current.x, a, 0.0, false)?;
            if !free.within_bound() || !with_prior {
                return Some(free);
            }
            Some(fit_artefact(pr, spec, &current.x, a, free.g, true).unwrap_or(free))
        })
        .collect()
}

/// Fits one artefact jointly with model `spec` from the model parameters `x0` and artefact
/// parameter `g0`, with its prior when `prior`. `None` when the design cannot show it (drift
/// without a run order) or the fit fails.
pub(crate) fn fit_artefact(
    pr: &Problem<'_>,
    spec: &Spec,
    x0: &[f64],
    artefact: Artefact,
    g0: f64,
    prior: bool,
) -> Option<ArtefactFit> {
    let basis = match artefact {
        Artefact::Gain | Artefact::CuttingGain | Artefact::FeedGain => vec![1.0; pr.tests.len()],
        Artefact::Drift => spec.ctx.wear_state.clone()?,
    };
    let (mut names, mut lo, mut hi, _) = layout(pr.sim, spec);
    names.push("instrument.g".into());
    lo.push(-G_BOUND);
    hi.push(G_BOUND);
    let bounds = Bounds::new(names, lo, hi).ok()?;
    let mut start = x0.to_vec();
    start.push(g0.clamp(-G_BOUND, G_BOUND));
    let opts = LmOptions {
        max_iterations: pr.cfg.max_iterations,
        gradient_tolerance: 1e-8,
        cost_tolerance: 1e-10,
        step_tolerance: 1e-9,
    };
    let problem = ArtefactProblem { pr, spec, basis, channels: artefact.channels(), prior };
    let r = minimise(&problem, &bounds, &DVector::from_vec(start.clone()), &opts).ok()?;
    let mut out = DVector::zeros(problem.residual_count());
    problem.residuals(&r.params, &mut out).ok()?;
    let rss: f64 = out.iter().take(pr.obs.len()).map(|v| v * v).sum();
    let penalty: f64 = out.iter().skip(pr.obs.len()).map(|v| v * v).sum();
    (rss.is_finite() && penalty.is_finite()).then(|| ArtefactFit {
        artefact,
        g: r.params[r.params.len() - 1],
        rss,
        penalty,
        k: start.len(),
        prior,
    })
}

/// Whether an instrument artefact stops the claim of candidate `best` of `cands` (issue 10,
/// decoys), on top of the current model `current` (its spec and fit). The artefacts inside their
/// bound ([`ArtefactFit::within_bound`]) whose AICc comes within the ambiguity margin of the
/// candidate's compete; one on its bound adds a note instead. The best competitor stops the claim
/// only when the mechanism adds nothing significant on top of it: the mechanism refitted jointly
/// with the artefact against the artefact alone, by the claim's own F-test at level `alpha` (a
/// nested comparison, as the refit's). A gain held at its bound while an edge force or a thermal
/// trend is left in the residuals is no explanation. When it stops the claim, the candidate's
/// `stopped_by` and reason are set; every finding goes to `notes`.
pub(crate) fn stops_claim(
    pr: &Problem<'_>,
    current: (&Spec, &Fit),
    cands: &mut [Candidate],
    best: usize,
    alpha: f64,
    notes: &mut Vec<String>,
) -> bool {
    let (spec, fit) = current;
    let n = pr.n();
    let base_aicc = stats::aicc(fit.objective(), n, fit.k);
    let c = &cands[best];
    let with_prior = c.id != MechanismId::ForceCrosstalk;
    let (inside, beyond): (Vec<_>, Vec<_>) = fit_artefacts(pr, fit, spec, with_prior)
        .into_iter()
        .filter(|a| a.aicc(n) - base_aicc - c.daicc < pr.cfg.ambiguity_delta_aicc)
        .partition(ArtefactFit::within_bound);
    notes.extend(beyond.iter().map(|a| a.on_bound_note(c.id.as_str())));
    let Some(a) = inside.into_iter().min_by(|x, y| x.aicc(n).total_cmp(&y.aicc(n))) else {
        return false;
    };
    let da = a.aicc(n) - base_aicc;
    let beyond = fit_artefact(pr, &c.spec, &c.fit.x, a.artefact, a.g, a.prior).map(|j| {
        let d = tested_df(c.id, j.k.saturating_sub(a.k));
        f_test(a.rss, j.rss, d, n, j.k + grid_chosen(c.id, &c.spec.ctx), boundary_params(c.id))
    });
    let id = c.id.as_str();
    if let Some(p) = beyond.filter(|p| p.is_finite() && *p < alpha) {
        notes.push(format!(
            "Instrument check: {} explains the mismatch about as well as {id}, but {id} adds significantly on top \
             of it (p = {p:.2e} < {alpha:.4}), so the artefact does not stop the claim.",
            a.artefact.describe(),
        ));
        return false;
    }
    notes.push(format!(
        "Instrument check: {} explains the mismatch at least as well as {id} (dAICc {da:+.1} against {:+.1}), so \
         no physics is claimed; check the dynamometer calibration{}.",
        a.artefact.describe(),
        c.daicc,
        if a.artefact == Artefact::Drift { " and repeat the first test at the end of the series" } else { "" }
    ));
    let c = &mut cands[best];
    c.reason = format!(
        "{} explains the mismatch at least as well (its dAICc {da:+.1} against {:+.1}; fitted factor {:.3}): no claim",
        a.artefact.describe(),
        c.daicc,
        a.g.exp()
    );
    c.stopped_by = Some(a.artefact);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aicc_counts_the_artefact_parameter() {
        // AICc = n ln(RSS/n) + 2k + 2k(k+1)/(n-k-1) (Hurvich & Tsai 1989): for n = 20, RSS = 20,
        // k = 3 the first term is 0 and the rest 6 + 24/16 = 7.5.
        let a = ArtefactFit { artefact: Artefact::Gain, g: 0.1, rss: 20.0, penalty: 0.0, k: 3, prior: false };
        assert!((a.aicc(20) - stats::aicc(20.0, 20, 3)).abs() < 1e-12);
        assert!((a.aicc(20) - 7.5).abs() < 1e-9, "{}", a.aicc(20));
    }

    /// Fits the artefacts on six tests whose recorded forces are `gain_fc` and `gain_ft` times a
    /// Mode A simulation's (+-2 % deterministic scatter on Fc, none on Ft and the chip), over a
    /// baseline with no parameters.
    fn artefacts_read_through(gain_fc: f64, gain_ft: f64, with_prior: bool) -> Vec<ArtefactFit> {
        use crate::context::Context;
        use crate::diagnose::Config;
        use crate::fit::observations;
        use crate::problem::condition_groups;
        use crate::simulator::{FixedSimulation, Prediction};
        use cutcal_model::CuttingTest;
        let (mut tests, mut entries) = (Vec::new(), Vec::new());
        for i in 0..6 {
            let (fc, ft, chip) = (2.0e5 + 2.0e4 * i as f64, 1.0e5, 2.0e-4);
            let scatter = if i % 2 == 0 { 1.02 } else { 0.98 };
            let t = CuttingTest::new(format!("{i}"), 1.0 + 0.5 * i as f64, 1e-4, 2e-3, 0.0)
                .and_then(|t| t.with_forces(Some(fc * gain_fc * scatter), Some(ft * gain_ft)))
                .and_then(|t| t.with_chip_thickness(Some(chip)))
                .unwrap();
            tests.push(t);
            let p =
                Prediction { fc_n_per_m: fc, ft_n_per_m: ft, chip_m: chip, t_ab_c: None, t_int_c: None, beta: None };
            entries.push((format!("{i}"), p));
        }
        let sim = FixedSimulation::new(entries, false).unwrap();
        let cfg = Config::standard("A");
        let pr = Problem {
            sim: &sim,
            tests: &tests,
            obs: observations(&tests),
            groups: condition_groups(&tests),
            cfg: &cfg,
        };
        let spec = Spec { mechanisms: Vec::new(), ctx: Context::of(&tests) };
        let base = pr.fit(&spec, None).unwrap();
        fit_artefacts(&pr, &base, &spec, with_prior)
    }

    #[test]
    fn a_gain_inside_its_bound_pays_its_prior() {
        // Forces read 10 % high. The residuals are ln ratios over the noise (3 % Fc, 5 % Ft), so
        // the gain's information is 6 / 0.03^2 + 6 / 0.05^2 = 9067 and the prior's (sd ln(1.2) / 2
        // = 0.09116) 1 / 0.09116^2 = 120.3. The data alone give 0.0952 (ln 1.1 with the Fc
        // scatter's weighted mean, -1.5e-4); the posterior mode is 0.0952 x 9067 / (9067 + 120.3)
        // = 0.0939, and the fit pays (0.0939 / 0.09116)^2 = 1.06.
        let fits = artefacts_read_through(1.1, 1.1, true);
        let kinds: Vec<Artefact> = fits.iter().map(|a| a.artefact).collect();
        assert_eq!(kinds, [Artefact::Gain, Artefact::CuttingGain, Artefact::FeedGain], "no run order, no drift");
        let a = &fits[0];
        assert!(a.prior && a.within_bound());
        assert!((a.g - 0.0939).abs() < 5e-4, "{}", a.g);
        assert!((a.penalty - (a.g / G_PRIOR_SD).powi(2)).abs() < 1e-9, "{} {}", a.penalty, a.g);
        assert!((a.penalty - 1.06).abs() < 0.01, "{}", a.penalty);
        // Against the cross-talk (no prior of its own) the gain competes without its prior too:
        // the data's own 0.0952, at no cost.
        let free = &artefacts_read_through(1.1, 1.1, false)[0];
        assert!(!free.prior && free.penalty.abs() < 1e-12, "{free:?}");
        assert!((free.g - 0.0952).abs() < 5e-4, "{}", free.g);
    }

    #[test]
    fn the_prior_does_not_pull_a_gain_off_its_bound() {
        // Forces read 30 % high: the data want a gain beyond the 20 % bound, so the fit presses
        // against it. That is judged without the prior (which would pull the estimate inside and
        // make a physical mismatch look like a calibration error): the fit is returned as it is.
        let fits = artefacts_read_through(1.3, 1.3, true);
        let a = &fits[0];
        assert!(!a.prior && !a.within_bound(), "{a:?}");
        assert!(a.penalty.abs() < 1e-12);
    }

    #[test]
    fn a_gain_on_one_channel_is_fitted_on_that_channel_alone() {
        // Only the feed force reads 10 % high. The feed channel's gain sees Ft alone: information
        // 6 / 0.05^2 = 2400 against the prior's 120.3, so the mode is ln 1.1 x 2400 / 2520.3 =
        // 0.09531 x 0.95227 = 0.09076, and the fit leaves Fc's scatter alone: its RSS is Fc's
        // +-2 % over 3 %, 3 x ((0.019803 / 0.03)^2 + (0.020203 / 0.03)^2) = 3 x (0.4357 + 0.4535)
        // = 2.668 (ln 1.02, ln 0.98), plus Ft's shortfall ((0.09531 - 0.09076) / 0.05)^2 six times,
        // 0.050: 2.717. The common gain has to split the difference between the channels and fits
        // worse.
        let fits = artefacts_read_through(1.0, 1.1, true);
        let feed = fits.iter().find(|a| a.artefact == Artefact::FeedGain).unwrap();
        let common = fits.iter().find(|a| a.artefact == Artefact::Gain).unwrap();
        let cutting = fits.iter().find(|a| a.artefact == Artefact::CuttingGain).unwrap();
        assert!((feed.g - 0.09076).abs() < 5e-4, "{}", feed.g);
        assert!((feed.rss - 2.717).abs() < 0.005, "{}", feed.rss);
        assert!(feed.aicc(18) < common.aicc(18) - 10.0, "{feed:?} {common:?}");
        assert!(cutting.g.abs() < 0.01 && cutting.aicc(18) > common.aicc(18), "{cutting:?} {common:?}");
    }

    #[test]
    fn a_factor_on_its_bound_is_no_instrument_explanation() {
        // ln 1.2 is the bound: 1.15 and 1/1.15 are inside it, 1.2 and 1/1.2 (a fit pressing
        // against it) are not.
        let fit = |factor: f64| ArtefactFit {
            artefact: Artefact::Gain,
            g: factor.ln(),
            rss: 1.0,
            penalty: 0.0,
            k: 2,
            prior: false,
        };
        assert!(fit(1.15).within_bound() && fit(1.0 / 1.15).within_bound());
        assert!(!fit(1.2).within_bound() && !fit(1.0 / 1.2).within_bound());
    }
}
