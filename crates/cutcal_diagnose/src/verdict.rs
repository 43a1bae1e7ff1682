//! The verdict of a diagnosis (design note Sec 3.7): missing physics when a mechanism was
//! accepted, ambiguous when near-equivalent rivals tie, and otherwise unexplained or none by the
//! global misfit. With too few conditions for the held-out check (fewer than 3), the mechanisms
//! that could explain the misfit as a whole are listed instead of claimed.

use crate::fit::{Fit, Obs, OUTPUTS};
use crate::mechanism::{info, MechanismId};
use crate::problem::Candidate;
use crate::report::{GlobalMisfit, Mismatch, Verdict};

/// A later round's best candidate `best` is not claimed when a mechanism held back in the same round
/// as a confounder of an earlier claim explains the remaining misfit better (lower AICc): what
/// remains is then more likely the earlier claim's own form than a further mechanism, the reason the
/// confounder was held back. Returns that confounder.
pub(crate) fn outdone_by_held_back(cands: &[Candidate], best: usize) -> Option<usize> {
    (0..cands.len())
        .filter(|&i| cands[i].held_back_for.is_some() && cands[i].daicc < cands[best].daicc)
        .min_by(|&a, &b| cands[a].daicc.total_cmp(&cands[b].daicc))
}

/// The verdict from the accepted mechanisms, the round-0 ambiguity list (extended here when there
/// is no held-out check), whether held-out validation was possible (`validated`), the global and
/// per-output misfits of the baseline `base` (residuals on `obs`) and the first round's candidates.
#[allow(clippy::too_many_arguments)]
pub(crate) fn decide(
    accepted: &[MechanismId],
    ambiguous: &mut Vec<MechanismId>,
    validated: bool,
    global: &GlobalMisfit,
    mismatch: &[Mismatch],
    first_round: &[Candidate],
    obs: &[Obs],
    base: &Fit,
) -> Verdict {
    let structured = global.p_value < 1e-3 || mismatch.iter().any(|m| m.p_value < 1e-3);
    let mut verdict = if !accepted.is_empty() {
        Verdict::MissingPhysics
    } else if !ambiguous.is_empty() {
        Verdict::Ambiguous
    } else if !validated && global.p_value < 0.01 {
        // Too few conditions to validate anything: list what could explain the misfit as a whole,
        // or the sign of a clearly missed output (its screening sensitivity points the same way
        // and carries at least 30 % of the mechanism's largest effect, and its refit explains at
        // least 20 % of the misfit).
        for m in mismatch.iter().filter(|m| m.p_value < 0.01) {
            let j = OUTPUTS.iter().position(|o| *o == m.output).unwrap_or(0);
            let idx: Vec<usize> = (0..obs.len()).filter(|&i| obs[i].output == j).collect();
            for c in first_round {
                let smax = c.sens.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                let agree = idx.iter().all(|&i| {
                    // The residual is measured - model; a mechanism adding model output s moves the
                    // residual by -s, so it explains the gap when s has the sign of the residual.
                    -c.sens[i] * base.resid[i] > 0.0 && c.sens[i].abs() >= 0.3 * smax
                });
                if agree && c.explained >= 0.2 && !idx.is_empty() && !ambiguous.contains(&c.id) {
                    ambiguous.push(c.id);
                }
            }
        }
        for c in first_round {
            let moved = c
                .fit
                .x
                .iter()
                .skip(base.k)
                .zip(info(c.id).params.iter())
                .any(|(v, pi)| (v - pi.off).abs() > 1e-3 * (pi.upper - pi.lower));
            if c.explained >= 0.5 && moved && !ambiguous.contains(&c.id) {
                ambiguous.push(c.id);
            }
        }
        if ambiguous.is_empty() {
            Verdict::Unexplained
        } else {
            Verdict::Ambiguous
        }
    } else if structured {
        Verdict::Unexplained
    } else {
        Verdict::None
    };
    if verdict == Verdict::Ambiguous && ambiguous.len() == 1 && validated {
        verdict = Verdict::Unexplained;
    }
    verdict
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::FitStatus;

    fn global(p_value: f64) -> GlobalMisfit {
        GlobalMisfit { chi2: 10.0, dof: 10, p_value }
    }

    fn base() -> Fit {
        Fit {
            x: vec![0.0],
            resid: vec![0.5, -0.5],
            rss: 0.5,
            penalty: 0.0,
            k: 1,
            preds: Vec::new(),
            status: FitStatus::Converged,
        }
    }

    #[test]
    fn verdict_follows_claims_ties_and_the_global_misfit() {
        let f = |acc: &[MechanismId], amb: &[MechanismId], validated: bool, p: f64| {
            let mut a = amb.to_vec();
            decide(acc, &mut a, validated, &global(p), &[], &[], &[], &base())
        };
        let (e, w) = (MechanismId::EdgePloughing, MechanismId::FlankWear);
        assert_eq!(f(&[e], &[], true, 1e-9), Verdict::MissingPhysics);
        assert_eq!(f(&[], &[e, w], true, 1e-9), Verdict::Ambiguous);
        // One name left of a tie after validation is no ambiguity: the misfit stays unexplained.
        assert_eq!(f(&[], &[e], true, 1e-9), Verdict::Unexplained);
        // Nothing claimed: structured misfit (p < 1e-3) is unexplained, anything else none.
        assert_eq!(f(&[], &[], true, 1e-4), Verdict::Unexplained);
        assert_eq!(f(&[], &[], true, 0.2), Verdict::None);
        // Too few conditions and a clear misfit, but no candidate to list: unexplained.
        assert_eq!(f(&[], &[], false, 1e-3), Verdict::Unexplained);
    }
}
