//! The breakdowns of a family's naming beside its headline (`super::summarise`): by bins of a
//! per-dataset measure (ENR, ENR beyond nuisance, the nearest rival's sum of squares), by the cause
//! of each miss, and by the shadow's fit to the simulation.

use std::fmt::Write as _;

use super::super::mechanism::MECHANISMS;
use super::{pct, Outcome};

/// A table of detection, claims and naming per bin `[lo, hi)` of `key`; a dataset whose key is
/// `None` is in no bin.
pub(super) fn binned(
    s: &mut String,
    label: &str,
    bins: &[(f64, f64, &str)],
    mech: &[&Outcome],
    key: impl Fn(&Outcome) -> Option<f64>,
) {
    let _ = writeln!(s, "\n| {label} | n | detected (verdict not `none`) | a mechanism claimed | named correctly |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for &(lo, hi, bin) in bins {
        let rows: Vec<&&Outcome> = mech.iter().filter(|o| key(o).is_some_and(|e| (lo..hi).contains(&e))).collect();
        let det = rows.iter().filter(|o| o.ok() && o.verdict.as_deref() != Some("none")).count();
        let cl = rows.iter().filter(|o| o.claims()).count();
        let nm = rows.iter().filter(|o| o.named()).count();
        let n = rows.len();
        let _ = writeln!(s, "| {bin} | {n} | {} | {} | {} |", pct(det, n), pct(cl, n), pct(nm, n));
    }
}

/// Naming against the sum of squares the nuisance and the nearest rival mechanism, in the
/// generator's own form, leave of the effect (`detectable::nearest_rival`), binned on Burnham &
/// Anderson's (2002) AICc scale: below 2 the data support both forms, so the name is a guess for
/// any detector; 2-10 considerably less support for the rival; above 10 essentially none.
pub(super) fn by_rival(s: &mut String, mech: &[&Outcome]) {
    let strong: Vec<&Outcome> = mech.iter().copied().filter(|o| o.strong()).collect();
    let confusable = strong.iter().filter(|o| o.rival_chi2.is_some_and(|e| e < 2.0)).count();
    let _ = writeln!(
        s,
        "\n**Naming against the nearest rival** (`detectable::nearest_rival`: the sum of squares, in noise units, \
         that the nuisance and the rival mechanism in this generator's own form, linearised, leave of the \
         noise-free effect; about the AICc by which the hidden form beats the rival's). Of the ENR >= 2 \
         datasets, {} leave less than 2, where the data support both forms (Burnham & Anderson 2002).",
        pct(confusable, strong.len())
    );
    let bins = [(0.0, 2.0, "[0, 2)"), (2.0, 10.0, "[2, 10)"), (10.0, f64::INFINITY, ">= 10")];
    binned(s, "rival's sum of squares, ENR >= 2", &bins, &strong, |o| o.rival_chi2);
}

/// Why a mechanism dataset at ENR >= 2 was not named (`None` when it was).
pub(super) fn miss_cause(o: &Outcome) -> Option<usize> {
    if o.named() {
        None
    } else if !o.ok() {
        Some(4)
    } else if o.ambiguous_with.contains(&o.hidden) {
        Some(0)
    } else if !o.selected.is_empty() {
        Some(1)
    } else if o.enr_beyond_nuisance.is_some_and(|e| e < 1.0) {
        Some(2)
    } else {
        Some(3)
    }
}

/// The misses at ENR >= 2 by cause, per mechanism: what the data could not separate (`ambiguous`
/// with the truth among the near-equivalent rivals), a wrong name, nothing claimed where the stated
/// nuisance reproduces the effect (ENR beyond nuisance < 1, `detectable.rs`), nothing claimed
/// otherwise, and diagnosis errors.
pub(super) fn misses_by_cause(s: &mut String, mech: &[&Outcome]) {
    let _ = writeln!(
        s,
        "\n**Misses at ENR >= 2 by cause:** `ambiguous` with the truth among the near-equivalent rivals; \
         another mechanism named; nothing claimed where the stated nuisance reproduces the effect (ENR \
         beyond nuisance < 1); nothing claimed otherwise; diagnosis error.\n"
    );
    let _ = writeln!(
        s,
        "| mechanism | missed | ambiguous, truth among the rivals | another named | nothing claimed, ENR beyond nuisance < 1 | nothing claimed, ENR beyond nuisance >= 1 | diagnosis error |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    let mut total = [0usize; 5];
    let mut row = |label: &str, rows: Vec<&&Outcome>, total: &mut [usize; 5]| {
        let mut c = [0usize; 5];
        for o in &rows {
            if let Some(k) = miss_cause(o) {
                c[k] += 1;
                total[k] += 1;
            }
        }
        let missed: usize = c.iter().sum();
        let _ =
            writeln!(s, "| {label} | {missed}/{} | {} | {} | {} | {} | {} |", rows.len(), c[0], c[1], c[2], c[3], c[4]);
    };
    let strong = |o: &&&Outcome| o.strong();
    for id in MECHANISMS {
        row(id, mech.iter().filter(strong).filter(|o| o.hidden == id).collect(), &mut total);
    }
    let n = mech.iter().filter(strong).count();
    let missed: usize = total.iter().sum();
    let _ = writeln!(
        s,
        "| all | {missed}/{n} | {} | {} | {} | {} | {} |",
        total[0], total[1], total[2], total[3], total[4]
    );
}

/// Naming at ENR >= 2 and clean nulls by the shadow's fitted RMS against the simulation
/// (`shadow_rms_pct`): the signatures come from the shadow, so naming follows its fidelity.
pub(super) fn by_shadow_fidelity(s: &mut String, mech: &[&Outcome], nulls: &[&Outcome]) {
    let _ = writeln!(
        s,
        "\n**By the shadow's fit to the simulation** (`shadow_rms_pct`, the fitted shadow's RMS against \
         `simulation.csv`; the signatures come from the shadow):\n"
    );
    let _ = writeln!(s, "| shadow RMS | named at ENR >= 2 | nulls with nothing selected |");
    let _ = writeln!(s, "|---|---|---|");
    let bins =
        [(0.0, 3.0, "below 3 %"), (3.0, 6.0, "3-6 %"), (6.0, 10.0, "6-10 %"), (10.0, f64::INFINITY, "10 % and above")];
    for (lo, hi, label) in bins {
        let inside = |o: &&&Outcome| o.shadow_rms_pct.is_some_and(|r| (lo..hi).contains(&r));
        let m: Vec<&&Outcome> = mech.iter().filter(|o| o.strong()).filter(inside).collect();
        let n: Vec<&&Outcome> = nulls.iter().filter(inside).collect();
        let _ = writeln!(
            s,
            "| {label} | {} | {} |",
            pct(m.iter().filter(|o| o.named()).count(), m.len()),
            pct(n.iter().filter(|o| o.ok() && o.selected.is_empty()).count(), n.len())
        );
    }
    let none = mech.iter().filter(|o| o.strong() && o.shadow_rms_pct.is_none()).count();
    if none > 0 {
        let _ = writeln!(s, "\n{none} mechanism datasets at ENR >= 2 have no shadow (or no report).");
    }
}
