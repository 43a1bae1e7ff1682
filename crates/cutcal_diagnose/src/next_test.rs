//! The report's next test: the one that would confirm a claim or separate the rivals (T-optimal
//! design, Atkinson & Fedorov 1975), the instrument check that comes before new cuts, or what to
//! measure when the mismatch fits no library mechanism.

use cutcal_model::CuttingTest;

use crate::fit::{self, output, Fit, Spec};
use crate::instrument::Artefact;
use crate::mechanism::MechanismId;
use crate::problem::{Candidate, Problem};
use crate::report::Verdict;
use crate::separate::{own_test, runner_up_test, separating_test, Recorded};

#[allow(clippy::too_many_arguments)] // the report's assembled pieces, one call site
pub(crate) fn next_test(
    pr: &Problem<'_>,
    verdict: Verdict,
    accepted: &[MechanismId],
    ambiguous: &[MechanismId],
    cands: &[Candidate],
    base: &Fit,
    base_spec: &Spec,
    current: &Fit,
    current_spec: &Spec,
    alpha: f64,
) -> String {
    let find = |m: MechanismId| cands.iter().find(|c| c.id == m);
    match verdict {
        Verdict::None if cands.iter().any(|c| c.stopped_by.is_some()) => {
            unexplained_next_test(pr, cands, base, base_spec)
        }
        Verdict::None => {
            crate::detect::interface_temperature_test(pr, base, base_spec, cands, alpha).unwrap_or_else(|| {
                "none needed: no significant mismatch; add conditions only to widen the validated range".into()
            })
        }
        Verdict::Unexplained => unexplained_next_test(pr, cands, base, base_spec),
        Verdict::MissingPhysics => {
            let m = accepted[0];
            let rec = Recorded::of(pr.tests);
            let confirm = match t_optimal(pr, (&base_spec.clone(), &base.x), (current_spec, &current.x)) {
                Some(s) => format!(
                    "confirm {} with a test at {s} where the corrected and uncorrected models differ most",
                    m.as_str()
                ),
                None => format!("confirm {}: {}", m.as_str(), own_test(m, rec)),
            };
            // A confounded runner-up close behind the claim (`separate::runner_up_test`).
            match runner_up_test(cands, m, rec) {
                Some(sep) => format!("{confirm}; {sep}"),
                None => confirm,
            }
        }
        Verdict::Ambiguous => {
            let mut parts = Vec::new();
            if ambiguous.len() >= 2 {
                if let (Some(a), Some(b)) = (find(ambiguous[0]), find(ambiguous[1])) {
                    if let Some(s) = t_optimal(pr, (&a.spec, &a.fit.x), (&b.spec, &b.fit.x)) {
                        parts.push(format!("a test at {s} separates {} from {}", a.id.as_str(), b.id.as_str()));
                    }
                }
            }
            // The measurement in which the best rival and each other one differ in kind
            // (`crate::separate`); a mechanism no such pair covers keeps its own test.
            let recorded = Recorded::of(pr.tests);
            let mut covered = Vec::new();
            if let Some((&first, rest)) = ambiguous.split_first() {
                for &m in rest {
                    if let Some(t) = separating_test(first, m, recorded) {
                        parts.push(format!("to separate {} from {}, {t}", first.as_str(), m.as_str()));
                        covered.extend([first, m]);
                    }
                }
            }
            for m in ambiguous.iter().filter(|m| !covered.contains(m)) {
                parts.push(format!("{}: {}", m.as_str(), own_test(*m, recorded)));
            }
            parts.join("; ")
        }
    }
}

/// The next test when nothing was claimed although the misfit is structured. A significant
/// candidate stopped by an instrument artefact asks first for the dead-weight check of the force
/// channels (ISO 21612: an instrument error is cheaper to rule out than new cuts); one that failed
/// only the held-out check asks for the condition where it and the baseline differ most
/// (T-optimal); otherwise the misfit fits no library mechanism.
fn unexplained_next_test(pr: &Problem<'_>, cands: &[Candidate], base: &Fit, base_spec: &Spec) -> String {
    let mut fitting: Vec<&Candidate> = cands.iter().filter(|c| c.significant && c.ci_ok && !c.accepted).collect();
    fitting.sort_by(|a, b| a.daicc.total_cmp(&b.daicc));
    let conditions = pr.groups.len();
    let recorded = Recorded::of(pr.tests);
    if let Some((c, a)) = fitting.iter().find_map(|c| c.stopped_by.map(|a| (c, a))) {
        let drift = if a == Artefact::Drift { " and repeat the first test at the end of the series" } else { "" };
        let check = format!("check the force channels with dead weights in each direction (ISO 21612){drift}");
        let artefact = a.describe();
        let id = c.id.as_str();
        return if c.id == MechanismId::ForceCrosstalk {
            format!(
                "{check}: {artefact} explains the mismatch at least as well as a cross-talk between the force \
                 channels, and the same check tells them apart"
            )
        } else {
            format!(
                "{check}: {artefact} explains the mismatch as well as {id} does; if the channels hold their \
                 calibration, {id} is the candidate ({})",
                own_test(c.id, recorded)
            )
        };
    }
    if let Some(c) = fitting.first() {
        let at = t_optimal(pr, (base_spec, &base.x), (&c.spec, &c.fit.x))
            .map_or_else(|| " beyond the present feeds and speeds".to_string(), |s| format!(", the first at {s}"));
        return format!(
            "{} fits these data (p = {:.2e}) but fails the held-out check (leave one condition out) \
             with {conditions} conditions: add conditions{at}; then {}",
            c.id.as_str(),
            c.p,
            own_test(c.id, recorded)
        );
    }
    // Ask only for what the recordings do not hold already.
    let missing: Vec<&str> = [
        (!recorded.edge_radius).then_some("the edge radius"),
        (!recorded.flank_wear).then_some("the flank wear"),
        (!recorded.interface_temperature).then_some("the interface temperature"),
    ]
    .into_iter()
    .flatten()
    .collect();
    let measure = match missing.as_slice() {
        [] => String::new(),
        [one] => format!("measure {one}, and "),
        [init @ .., last] => format!("measure {} and {last}, and ", init.join(", ")),
    };
    format!(
        "the mismatch fits no library mechanism: {measure}add feeds and speeds outside the present range \
         ({conditions} conditions now)"
    )
}

/// The condition of a small grid around the design where two fitted models differ most
/// (T-optimal discrimination, Atkinson & Fedorov 1975); `None` if the simulator cannot extrapolate.
pub(crate) fn t_optimal(pr: &Problem<'_>, a: (&Spec, &[f64]), b: (&Spec, &[f64])) -> Option<String> {
    if !pr.sim.can_extrapolate() {
        return None;
    }
    let t0 = pr.tests.first()?;
    let hs: Vec<f64> = pr.tests.iter().map(|t| t.uncut_chip_thickness_m).collect();
    let vs: Vec<f64> = pr.tests.iter().map(|t| t.speed_m_per_s).collect();
    let (hmin, hmax) = (hs.iter().cloned().fold(f64::INFINITY, f64::min), hs.iter().cloned().fold(0.0, f64::max));
    let (vmin, vmax) = (vs.iter().cloned().fold(f64::INFINITY, f64::min), vs.iter().cloned().fold(0.0, f64::max));
    let grid = |lo: f64, hi: f64| -> Vec<f64> {
        (0..5).map(|i| (0.6 * lo) * ((1.6 * hi) / (0.6 * lo)).powf(i as f64 / 4.0)).collect()
    };
    let mut best: Option<(f64, String)> = None;
    for h in grid(hmin, hmax) {
        for v in grid(vmin, vmax) {
            let Ok(mut t) = CuttingTest::new("next", v, h.min(4.9e-3), t0.width_m, t0.rake_rad) else { continue };
            t.edge_radius_m = t0.edge_radius_m;
            let one = [t];
            let pred = |(spec, x): (&Spec, &[f64])| {
                let mut ctx = spec.ctx.clone();
                ctx.wear_state = ctx.wear_state.map(|_| vec![1.0]);
                fit::predict(pr.sim, &one, &Spec { mechanisms: spec.mechanisms.clone(), ctx: ctx.clone() }, &ctx, x)
                    .ok()
            };
            let (Some(pa), Some(pb)) = (pred(a), pred(b)) else { continue };
            let mut dsum = 0.0;
            let mut diffs = [0.0; 3];
            for (j, d) in diffs.iter_mut().enumerate() {
                *d = 100.0 * (output(&pa[0], j) / output(&pb[0], j) - 1.0);
                dsum += ((output(&pa[0], j) / output(&pb[0], j)).ln() / pr.cfg.noise[j]).powi(2);
            }
            let text = format!(
                "h = {:.3} mm, V = {:.0} m/min (predictions differ by Fc {:+.1} %, Ft {:+.1} %, tc {:+.1} %)",
                h * 1e3,
                v * 60.0,
                diffs[0],
                diffs[1],
                diffs[2]
            );
            if best.as_ref().is_none_or(|(b, _)| dsum > *b) {
                best = Some((dsum, text));
            }
        }
    }
    best.map(|b| b.1)
}
